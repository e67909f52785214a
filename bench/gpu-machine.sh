#!/usr/bin/env bash
# The GPU-first figures and GPU tests on a machine with an NVIDIA GPU and no network, through the
# team's offline bundle (.gpu-bundle/: Node 24, the production node_modules, the Vulkan loader; see
# the bundle's README). Run in a copy of the project root that holds .gpu-bundle/ and the generated
# modules `npm run generate` writes (git-ignored: src/shaders/*.generated.ts, src/shaders/wgsl/, the
# OIDN weight modules under weights/oidn/ and src/film/denoise/oidn/, the codecs under src/io/gltf/codecs/):
#   bash bench/gpu-machine.sh [output directory]      (default bench/results/gpu-machine)
# Writes gpu-bench.txt and gpu-bench.json (bench/gpu.ts at the full workload: the table),
# gpu-tests.txt (the path tracer tests and the BSDF sampling test on the GPU), and nvidia-smi.txt.
set -u
out=${1:-bench/results/gpu-machine}
mkdir -p "$out"
bundle() { bash .gpu-bundle/run.sh "$@"; }
nvidia-smi > "$out/nvidia-smi.txt" 2>&1
BENCH_GPU_SCALE=1 bundle node bench/run.ts --gpu-only 2>&1 | tee "$out/gpu-bench.txt"
cp bench/results/bench.json "$out/gpu-bench.json"
bundle node --test --test-concurrency=1 test/pathtracer/*.test.ts test/materials/gltf-bsdf-sampling.test.ts 2>&1 | tee "$out/gpu-tests.txt" | grep -E '✖|ℹ (tests|pass|fail)'
