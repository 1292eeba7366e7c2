"""A 2D physics sandbox for teaching physics-based animation."""
