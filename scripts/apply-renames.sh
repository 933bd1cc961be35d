#!/bin/bash
# Applies scripts/renames.sed (issue 26's public renames) to every tracked C/C++ source, header,
# Python file, CMake file and document, then formats the C/C++ files it changed with the repo's
# .clang-format (longer names may push a line past the column limit). Idempotent: a second run
# changes nothing. Run from anywhere inside the work tree:
#   scripts/apply-renames.sh            every tracked file
#   CJ_RENAMES_SKIP='README.md' scripts/apply-renames.sh   all but the paths listed (spaces)
set -eu
top=$(git rev-parse --show-toplevel)
cd "$top"
sed_file=scripts/renames.sed
changed=$(mktemp)
trap 'rm -f "$changed"' EXIT
git ls-files -z -- '*.c' '*.h' '*.cpp' '*.hpp' '*.cc' '*.py' '*.md' '*.txt' '*.cmake' \
    '*.in' '*.sh' '*.bash-completion' |
    while IFS= read -r -d "" f; do
        [ -f "$f" ] || continue
        case " ${CJ_RENAMES_SKIP:-} " in *" $f "*) continue ;; esac
        [ "$f" = "$sed_file" ] && continue
        [ "$f" = scripts/apply-renames.sh ] && continue
        if ! sed -E -f "$sed_file" "$f" | cmp -s - "$f"; then
            sed -E -i -f "$sed_file" "$f"
            printf '%s\n' "$f" >>"$changed"
        fi
    done
n=$(wc -l <"$changed")
if command -v clang-format >/dev/null 2>&1; then
    grep -E '\.(c|h|cpp|hpp|cc)$' "$changed" | while IFS= read -r f; do clang-format -i "$f"; done
fi
echo "apply-renames: $n file(s) changed"
