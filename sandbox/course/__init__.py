"""The course as students and teachers meet it: lessons found wherever the package is installed,
run as scripts or executed as notebooks into ``outputs/``, rendered as offline HTML pages, and
gathered in a course book (``outputs/index.html``).

- :mod:`sandbox.course.catalogue`: which lessons exist, their titles and opening paragraphs
- :mod:`sandbox.course.runner`: running one lesson (a script, or an executed notebook)
- :mod:`sandbox.course.page`: an executed notebook as an HTML page that works offline
- :mod:`sandbox.course.markup`: the little Markdown and TeX those pages and cards need
- :mod:`sandbox.course.book`: the course book, one card per lesson
- :mod:`sandbox.course.links`: checking that the book works offline (links resolve, nothing fetched)
"""
