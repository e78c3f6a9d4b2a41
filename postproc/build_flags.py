"""The release build's compiler flags, one definition for the Python side (the tests'
fallback binary, boat_rao, the MPI test); make.sh and .ci/update_docs.sh spell the same
string (test_build_flags checks they agree).

-march=native: the wave kernels vectorise 3x better than with the x86-64 baseline;
-fstack-arrays: automatic arrays on the stack, not malloc, in the right-hand side;
-flto=auto: link-time optimisation inlines the small cross-module routines of the
right-hand side (cross products, rotation matrices, hook and cable kinematics): 0.73 x the
CPU time of a regular launch, 0.74 x single-summation, 0.88 x double-summation
(farm-bench, doc/benchmarks/index.md)."""

RELEASE_FLAGS = "-march=native -fstack-arrays -flto=auto"


def fpm_release(extra=""):
    """fpm's arguments for the release build, with `extra` flags appended."""
    flags = RELEASE_FLAGS + (" " + extra if extra else "")
    return ["--profile", "release", "--flag", flags]
