"""external_project's check of the installed Python module: python3 check-python-module.py PREFIX, with PYTHONPATH
set to the module's installed directory. Prints OK if the module imported is the prefix's, the library it loaded is
the prefix's, and a call works."""
import os
import sys

import visp_projective as vpp

prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(vpp.__file__).startswith(prefix + os.sep), f"module {vpp.__file__} is not under {prefix}"
with open("/proc/self/maps") as maps:
    libraries = {line.split()[-1] for line in maps if "libvisp_projective.so" in line}
assert libraries and all(os.path.realpath(p).startswith(prefix + os.sep) for p in libraries), libraries
robot = vpp.ProjectiveRobot([vpp.ProjectiveRobot.REVOLUTE, vpp.ProjectiveRobot.PRISMATIC])
assert robot.getNumberOfJoints() == 2 and robot.getJointType(1) == vpp.ProjectiveRobot.PRISMATIC
print("OK")
