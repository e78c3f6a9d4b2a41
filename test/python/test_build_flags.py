"""The release build's flags are spelled in three places (postproc/build_flags.py for the
Python side, make.sh, .ci/update_docs.sh): a binary built with other flags is a second
build, and the library's and the binary's links must optimise alike. They must agree."""
import pathlib
import re

from postproc.build_flags import RELEASE_FLAGS, fpm_release

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_make_sh_builds_with_the_release_flags():
    text = (ROOT / "make.sh").read_text()
    match = re.search(r'release_flags\(\) \{\n\s*echo "([^"]*)"', text)
    assert match, "make.sh defines release_flags()"
    assert match.group(1).replace("$DAVIT_MARCH", "native") == RELEASE_FLAGS
    # every fpm flag set of make.sh goes through it
    assert "-fstack-arrays\"" not in text.replace('echo "' + match.group(1) + '"', "")


def test_update_docs_builds_with_the_release_flags():
    text = (ROOT / ".ci" / "update_docs.sh").read_text()
    assert f'--flag "{RELEASE_FLAGS}"' in text


def test_fpm_arguments():
    assert fpm_release() == ["--profile", "release", "--flag", RELEASE_FLAGS]
    assert fpm_release("-DDAVIT_MPI")[-1] == RELEASE_FLAGS + " -DDAVIT_MPI"
