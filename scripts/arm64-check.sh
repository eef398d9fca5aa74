#!/usr/bin/env bash
# Builds sim/ for 64-bit ARM (aarch64) with Debian's cross compiler: the solver's kernels compile
# there for Highway's ARM targets (NEON, SVE, SVE2, ...), which no x86 build compiles. With --run it
# also runs the default scene on every ARM target under qemu-user and compares the strands with
# this machine's x86 build (issue 15: targets agree within 1e-4 m; it says whether the bits agree).
#
#   scripts/arm64-check.sh              compile sim/ for aarch64 (about 2 min on 2 cores); lists the
#                                       ARM targets compiled in
#   scripts/arm64-check.sh --run [N]    and run N steps (default 240) of the default scene on each
#                                       ARM target qemu-user emulates (NEON, SVE, SVE2; about 40 s
#                                       each), against build/'s x86 sim library (scripts/setup.sh)
#
# Installs what is missing from Debian's packages (as root, or through sudo): the cross compiler;
# for --run also qemu-user and Highway for arm64 (which adds arm64 to dpkg's architectures).
# Everything it builds goes to build-arm64/.
set -euo pipefail
cd "$(dirname "$0")/.."

run=0
steps=240
if [[ "${1:-}" == --run ]]; then
    run=1
    if [[ -n "${2:-}" ]]; then
        [[ "$2" =~ ^[1-9][0-9]*$ ]] || { echo "arm64-check: --run takes a number of steps, not '$2'" >&2; exit 2; }
        steps=$2
    fi
elif [[ -n "${1:-}" ]]; then
    sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
install() { # Debian packages, only those missing
    local missing=()
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if ((${#missing[@]})); then
        echo "== installing: ${missing[*]}"
        $SUDO apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
    fi
}
install g++-aarch64-linux-gnu libhwy-dev libglm-dev
if ((run)); then
    dpkg --print-foreign-architectures | grep -qx arm64 || $SUDO dpkg --add-architecture arm64
    install qemu-user libhwy-dev:arm64
fi

out=build-arm64
mkdir -p "$out/obj" "$out/include"
# The host's Highway and GLM headers serve the cross compiler (they are the same on every
# architecture), without the rest of /usr/include.
ln -sfn /usr/include/hwy "$out/include/hwy"
ln -sfn /usr/include/glm "$out/include/glm"
# The project's own flags (CMakeLists.txt): the same arithmetic as the x86 build.
flags=(-std=c++20 -O2 -ffp-contract=off -I. -isystem "$out/include" -DGLM_FORCE_XYZW_ONLY -DGLM_FORCE_CTOR_INIT)
export out
compile_one() { # $1: a source; its object in $out/obj, named after its path
    local object="$out/obj/$(echo "$1" | tr / _).o"
    if ! aarch64-linux-gnu-g++ "${flags[@]}" -c "$1" -o "$object" 2> "$object.log"; then
        echo "!! $1 does not compile for aarch64:" >&2
        cat "$object.log" >&2
        return 1
    fi
}
export -f compile_one
export flags_string="${flags[*]}"
sources=$(find sim -name '*.cpp' | sort)
((run)) && sources+=$'\n'tests/arm64/default-scene.cpp
echo "== compiling $(echo "$sources" | wc -l) files for aarch64 into $out/"
# (flags go through the environment as one string: bash cannot export an array)
echo "$sources" | xargs -P "$(nproc)" -I{} bash -c 'flags=($flags_string); compile_one "$1"' _ {}
targets=$(aarch64-linux-gnu-nm -C "$out/obj/sim_solver_SolverBlockKernel.cpp.o" | grep -o 'wisp::N_[A-Z0-9_]*' |
    sed 's/wisp::N_//' | sort -u | tr '\n' ' ')
echo "== sim/ compiles for aarch64; the solver's kernels for: $targets"
((run)) || exit 0

# The x86 side: the same program against build/'s sim library.
[ -f build/sim/libwisp_sim.a ] || { echo "arm64-check: no build/sim/libwisp_sim.a (run scripts/setup.sh)" >&2; exit 1; }
g++ -std=c++20 -O2 -I. -DGLM_FORCE_XYZW_ONLY -DGLM_FORCE_CTOR_INIT tests/arm64/default-scene.cpp \
    build/sim/libwisp_sim.a -lhwy -pthread -o "$out/default-scene-x86"
aarch64-linux-gnu-g++ "$out/obj/tests_arm64_default-scene.cpp.o" \
    $(find "$out/obj" -name 'sim_*.o' | sort) -L/usr/lib/aarch64-linux-gnu -lhwy -pthread -o "$out/default-scene-arm64"
qemu=(qemu-aarch64 -L /usr/aarch64-linux-gnu)

# One thread: Debian 12's qemu-user hangs in a guest's first pthread_create here (a three-line
# program's too), and the solver gives the same bits on any thread count (SimdTarget tests).
echo "== the default scene, $steps steps, one thread"
"$out/default-scene-x86" "$steps" 1 > "$out/x86.f32"
status=0
for target in $("${qemu[@]}" "$out/default-scene-arm64" --targets); do
    "${qemu[@]}" "$out/default-scene-arm64" "$steps" 1 "$target" > "$out/arm64-$target.f32"
    python3 - "$out/x86.f32" "$out/arm64-$target.f32" "$target" <<'EOF' || status=1
import struct, sys, math
a, b = (open(p, 'rb').read() for p in sys.argv[1:3])
if len(a) != len(b) or len(a) % 12:
    sys.exit(f"{sys.argv[3]}: {len(b) // 12} particles, x86 {len(a) // 12}")
fa, fb = struct.unpack(f'<{len(a) // 4}f', a), struct.unpack(f'<{len(b) // 4}f', b)
far = max(math.dist(fa[i:i + 3], fb[i:i + 3]) for i in range(0, len(fa), 3))
print(f"{sys.argv[3]} against x86: {len(a) // 12} particles, farthest apart {far:.3g} m, "
      f"{'the same bits' if a == b else 'not the same bits'}")
sys.exit(0 if far <= 1e-4 else 1)
EOF
done
exit $status
