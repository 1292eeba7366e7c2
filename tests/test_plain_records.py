"""The uncompiled engine's record view (sandbox.plain_records): numpy's values, read faster."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from sandbox.plain_records import Record, Records, fast_records
from sandbox.records import BODY, CONTACT


def filled_contacts(n: int = 4) -> np.ndarray:
    rng = np.random.default_rng(7)
    contacts = np.zeros(n, dtype=CONTACT)
    for name in ("friction", "inv_mass_a", "soft_bias_rate"):
        contacts[name] = rng.normal(size=n)
    contacts["normal"] = rng.normal(size=(n, 2))
    contacts["a"], contacts["count"] = np.arange(n) * 3, 2
    contacts["points"]["depth"] = rng.normal(size=(n, 2))
    contacts["points"]["point"] = rng.normal(size=(n, 2, 2))
    contacts["points"]["feature"] = rng.integers(-1, 1 << 40, size=(n, 2))
    contacts["use_block"] = [True, False, True, False][:n]
    return contacts


def test_every_read_gives_numpys_value():
    plain = filled_contacts()
    fast = fast_records(plain)
    assert isinstance(fast, Records) and isinstance(fast[1], Record)
    for i in range(len(plain)):
        for name in CONTACT.names:
            if CONTACT[name].names is not None or CONTACT[name].subdtype:
                continue
            assert fast[i][name] == plain[i][name], name  # exact, not close
        assert list(fast[i]["normal"]) == list(plain[i]["normal"])
        for j in range(2):
            p, q = fast[i]["points"][j], plain[i]["points"][j]
            assert p["depth"] == q["depth"] and p["feature"] == q["feature"]
            assert list(p["point"]) == list(q["point"])
    assert fast[np.int64(2)]["a"] == 6 and fast[-1]["a"] == 9  # numpy integers, from the end
    assert fast[0]["use_block"] is True and fast[1]["use_block"] is False


def test_writes_reach_the_array():
    plain = filled_contacts()
    fast = fast_records(plain)
    c = fast[2]
    c["friction"] = 0.25
    c["normal"][1] = -1.5
    c["points"][1]["depth"] = 0.125
    c["points"][0]["point"][0] = 3.0
    c["count"] = 1
    assert plain[2]["friction"] == 0.25 and plain[2]["normal"][1] == -1.5
    assert plain[2]["points"][1]["depth"] == 0.125 and plain[2]["points"][0]["point"][0] == 3.0
    assert plain[2]["count"] == 1
    assert plain[1]["friction"] != 0.25  # only the record written


def test_the_rest_is_an_ordinary_array():
    plain = filled_contacts()
    fast = fast_records(plain)
    assert np.array_equal(fast["friction"], plain["friction"])  # a field by name
    assert np.array_equal(fast[1:3]["a"], [3, 6])  # a slice
    assert fast.shape == plain.shape and np.shares_memory(fast, plain)
    with pytest.raises(IndexError):
        fast[4]
    with pytest.raises(IndexError):
        fast[0]["points"][2]
    pair = fast_records((np.zeros(2, dtype=BODY), np.zeros(3), [np.zeros(1, dtype=BODY)]))
    assert isinstance(pair[0], Records) and type(pair[1]) is np.ndarray
    assert isinstance(pair[2], list) and isinstance(pair[2][0], Records)


# a box pyramid and a ball on a pin chain (contacts and joints), iterative, soft and shock, stepped
# uncompiled: once through the record view (the engine's way) and once on numpy's own records
SCRIPT = """
import json, sys
import numpy as np
import sandbox.plain_records
from sandbox import Body, Box, Circle, World
from sandbox.joints import PinJoint

if sys.argv[1] == "numpy":
    sandbox.plain_records.fast_records = lambda value: value

out = {}
for solver in ("iterative", "soft", "shock"):  # shock: the staged path
    w = World(gravity=(0, -9.81), solver=solver)
    w.add_body(Body("g", type="static", position=(0, -0.5))).add_shape(Box(10, 1, friction=0.6))
    for row in range(3):
        for i in range(3 - row):
            box = Body(f"b{row}{i}", position=(i - 1 + 0.5 * row + 0.02, 0.5 + row))
            w.add_body(box).add_shape(Box(1, 1, friction=0.6))
    hook = w.add_body(Body("hook", type="static", position=(4, 4)))
    ball = w.add_body(Body("ball", position=(5, 4)))
    ball.add_shape(Circle(0.2))
    w.add_joint(PinJoint(hook, ball))
    for _ in range(30):
        w.step()
    out[solver] = [w.com.tobytes().hex(), w.vel.tobytes().hex(), w.omega.tobytes().hex()]
print(json.dumps(out))
"""


def test_uncompiled_steps_are_bit_identical_through_the_record_view():
    def run(records):
        env = dict(os.environ, SANDBOX_JIT="0")
        done = subprocess.run(
            [sys.executable, "-c", SCRIPT, records],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
        return json.loads(done.stdout)

    fast, numpy_records = run("fast"), run("numpy")
    assert fast == numpy_records
    start = np.zeros(2)
    assert fast["soft"][0] != start.tobytes().hex()  # sanity: the bodies moved


def test_a_record_prints_with_its_fields():
    fast = fast_records(filled_contacts())
    text = repr(fast[1])
    assert text.startswith("Record(a=3, b=0, count=2, normal=[")
    assert "points=<2 records>" in text and "use_block=False" in text
    assert repr(fast[1]["points"][0]).startswith("Record(rn_a=0.0")


def test_it_refuses_what_compiled_code_refuses():
    # a division by zero raises, as numba's default error model does (numpy's scalars would
    # give inf with a warning); a float is not cut to fit an integer field
    c = fast_records(np.zeros(1, dtype=CONTACT))[0]
    with pytest.raises(ZeroDivisionError):
        1.0 / c["friction"]
    with pytest.raises(TypeError):
        c["count"] = 1.5
    assert type(c["friction"]) is float and type(c["count"]) is int
