#pragma once
// Benchmark 12's 3602 paths: `daemon_bench slip3602 --stepmodd PATH [--runs 2] [--keep-trace VCD]`
// (bench/path_slip.cpp).
namespace stepmod::bench {
int path_slip(int argc, char** argv);
}
