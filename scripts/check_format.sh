#!/usr/bin/env bash
# Fails when a tracked C++ file differs from what the root .clang-format makes of it (Debian 12's
# clang-format 14; another major version formats some constructs differently). Fix with:
#   git ls-files '*.cpp' '*.h' | xargs clang-format-14 -i
set -euo pipefail
cd "$(dirname "$0")/.."
tool=$(command -v clang-format-14 || command -v clang-format || true)
if [ -z "$tool" ]; then
  echo "check_format: clang-format not found (scripts/install_deps.sh installs it)" >&2
  exit 1
fi
unformatted=()
while IFS= read -r f; do
  if ! "$tool" --style=file "$f" | cmp -s - "$f"; then unformatted+=("$f"); fi
done < <(git ls-files '*.cpp' '*.h')
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "check_format: ${#unformatted[@]} file(s) differ from .clang-format:" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  exit 1
fi
echo "check_format: $(git ls-files '*.cpp' '*.h' | wc -l) C++ files formatted"
