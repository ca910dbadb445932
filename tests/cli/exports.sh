#!/usr/bin/env bash
# libhemirad exports its API and nothing else (include/hemirad/visibility.h): at most 800
# dynamic symbols, none of glad's GL loader nor of the internal classes, and the public API's
# entry points among them.
set -euo pipefail
HEMIRAD="$1"
lib="$(dirname "$HEMIRAD")/libhemirad.so"
command -v nm >/dev/null || { echo "exports: nm (binutils) not found: skipped"; exit 77; }
[ -e "$lib" ] || { echo "exports: $lib not found"; exit 1; }

symbols=$(nm -D --defined-only "$lib")
count=$(wc -l <<<"$symbols")
echo "exports: $count dynamic symbols defined in $(basename "$(realpath "$lib")")"
[ "$count" -le 800 ] || { echo "exports: more than 800 symbols exported"; exit 1; }
if grep -i glad <<<"$symbols" | head -5 | grep .; then
    echo "exports: glad's GL loader is exported"; exit 1
fi
demangled=$(nm -DC --defined-only "$lib")
# Internals stay inside: the BVH, the GL wrappers, the hemicube renderer.
if grep -E 'hemirad::(Bvh|gl::(Buffer|Texture|Program|StateGuard)|gpu::)' <<<"$demangled" | head -5 | grep .; then
    echo "exports: internal classes are exported"; exit 1
fi
# The API is there.
for s in 'hemirad::Solver::step()' 'hemirad::load_scene(' 'hemirad::solver_option_table()' \
         'hemirad::gl::Context::create(' 'hemirad::InputError'; do
    grep -qF "$s" <<<"$demangled" || { echo "exports: $s is not exported"; exit 1; }
done
echo "exports: ok"
