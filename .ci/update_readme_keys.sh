#!/usr/bin/env bash
# Regenerate the README's deck-key tables from `davit keys` (test_readme checks they match).
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${DAVIT_BIN:-$(fpm run --profile release --flag "-march=native -fstack-arrays" --runner echo 2>/dev/null | tail -n 1)}"
python3 - "$bin" <<'PY'
import subprocess, sys
keys = subprocess.run([sys.argv[1], "keys"], capture_output=True, text=True, check=True).stdout
text = open("README.md").read()
head, rest = text.split("<!-- keys:start -->\n", 1)
_, tail = rest.split("<!-- keys:end -->", 1)
open("README.md", "w").write(head + "<!-- keys:start -->\n" + keys + "<!-- keys:end -->" + tail)
PY
