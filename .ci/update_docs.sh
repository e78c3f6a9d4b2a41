#!/usr/bin/env bash
# Regenerate the documentation's blocks made from the code (deck keys, davit --help,
# davit-post --help: postproc/doc_blocks.py); test/python/test_docs.py checks they match.
# The tables made from runs: davit-post readme-tables out --run --write (minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${DAVIT_BIN:-$PWD/$(fpm run --profile release --flag "-march=native -fstack-arrays -flto=auto" --runner echo 2>/dev/null | tail -n 1)}"
python3 -m postproc.doc_blocks --write --davit "$bin"
