"""The package sets libgomp's wait policy to PASSIVE when it is the one that
loads libgomp, and leaves a policy the user chose. libgomp prints what it
took with OMP_DISPLAY_ENV=VERBOSE; its spin count tells the policies apart
(300000 by default, 0 for PASSIVE, 30 billion for ACTIVE), where the
printed OMP_WAIT_POLICY reads 'PASSIVE' for the spinning default too."""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGE_ROOT = os.path.normpath(os.path.join(HERE, os.pardir))


def spin_count(code, env_policy):
    env = dict(os.environ, OMP_DISPLAY_ENV="VERBOSE", PYTHONPATH=PACKAGE_ROOT)
    env.pop("OMP_WAIT_POLICY", None)
    if env_policy:
        env["OMP_WAIT_POLICY"] = env_policy
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    lines = [l for l in out.stderr.splitlines() if "GOMP_SPINCOUNT" in l]
    assert lines, out.stderr
    return int(lines[0].split("=")[1].strip().strip("'"))


def test_passive_when_the_package_loads_libgomp():
    assert spin_count("import neuv", None) == 0


def test_user_policy_kept():
    assert spin_count("import neuv", "ACTIVE") > 300000


def test_libgomp_loaded_before_is_left_alone():
    """A process that has libgomp already keeps its policy (libgomp's default spins)."""
    code = "import ctypes, ctypes.util; ctypes.CDLL(ctypes.util.find_library('gomp')); import neuv"
    assert spin_count(code, None) == 300000
