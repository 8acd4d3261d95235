"""The code of the Python page of the documentation (docs/python.dox), run as it is written there."""
import os

import numpy as np

from conftest import TUTORIALS


def test_documented_acquire_and_servo():
    """The code of docs/python.dox, section python_acquire_servo, as it is written there."""
    with open(os.path.join(TUTORIALS, os.pardir, os.pardir, "docs", "python.dox")) as f:
        page = f.read()
    section = page[page.index("\\section python_acquire_servo"):]
    code = section[section.index("\\code{.py}") + len("\\code{.py}"):section.index("\\endcode")]
    namespace = {}
    exec(compile(code, "docs/python.dox", "exec"), namespace)
    task = namespace["task"]
    assert task.getStatus() == namespace["vpp"].ServoProjective.SERVO_RUNNING
    assert np.sqrt(np.mean(task.getError() ** 2)) < 0.1  # pixels
