#!/usr/bin/env python3
"""Writes docs/perf.md and its plots from the results bench/run_all.sh measured.

usage: bench/report.py RESULTS_DIR OUTPUT_MD

RESULTS_DIR holds matrix.jsonl, scaling.jsonl and variants.jsonl (the output of
`tessera bench --json --vs llvmpipe`, one object per line) and machine.json.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENE_ORDER = ["cube", "bunny", "dense", "fill", "textured"]
SCENE_WHAT = {
    "cube": "the unit cube",
    "bunny": "the Stanford bunny (glmark2-data)",
    "dense": "UV sphere of small triangles",
    "fill": "10 screen-covering quads, back to front (overdraw 10)",
    "textured": "UV sphere, 512x512 checker texture, bilinear",
}


def read_lines(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def ms(value):
    return f"{value:.2f}" if value < 100 else f"{value:.1f}"


def scene_key(row):
    name = row["scene"]
    order = SCENE_ORDER.index(name) if name in SCENE_ORDER else len(SCENE_ORDER)
    return (order, name, row["width"] * row["height"])


def plot_triangles(spheres, matrix, path):
    """The sphere sweep as lines, the built-in scenes as labelled points, all at 1920x1080."""
    fig, ax = plt.subplots(figsize=(7.5, 4.8), dpi=110)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    sweep = sorted(spheres, key=lambda r: r["triangles"])
    x = [r["triangles"] for r in sweep]
    ax.plot(x, [r["median_ms"] for r in sweep], "o-", color=colors[0],
            label="tessera, UV spheres")
    ax.plot(x, [r["llvmpipe_median_ms"] for r in sweep], "s--", color=colors[1],
            label="llvmpipe, UV spheres")
    scenes = [r for r in matrix if r["resolution"] == "1920x1080"]
    ax.plot([r["triangles"] for r in scenes], [r["median_ms"] for r in scenes], "o",
            color=colors[0], fillstyle="none", markersize=9, label="tessera, bench scenes")
    ax.plot([r["triangles"] for r in scenes], [r["llvmpipe_median_ms"] for r in scenes], "s",
            color=colors[1], fillstyle="none", markersize=9, label="llvmpipe, bench scenes")
    for r in scenes:
        ax.annotate(r["scene"], (r["triangles"], r["median_ms"]), fontsize=8,
                    textcoords="offset points", xytext=(6, -10))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("triangles in the scene")
    ax.set_ylabel("median frame time at 1920x1080 (ms)")
    ax.set_title("Frame time against triangle count")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_resolution(rows, path):
    fig, ax = plt.subplots(figsize=(7.5, 4.8), dpi=110)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    scenes = sorted({r["scene"] for r in rows},
                    key=lambda s: SCENE_ORDER.index(s) if s in SCENE_ORDER else 99)
    for i, scene in enumerate(scenes):
        sel = sorted((r for r in rows if r["scene"] == scene), key=lambda r: r["width"] * r["height"])
        x = [r["width"] * r["height"] / 1e6 for r in sel]
        ax.plot(x, [r["median_ms"] for r in sel], "o-", color=colors[i], label=f"tessera {scene}")
        ax.plot(x, [r["llvmpipe_median_ms"] for r in sel], "s--", color=colors[i], alpha=0.6,
                label=f"llvmpipe {scene}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("megapixels (640x480, 1920x1080, 3840x2160)")
    ax.set_ylabel("median frame time (ms)")
    ax.set_title("Frame time against resolution")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    results, output = sys.argv[1], sys.argv[2]
    matrix = sorted(read_lines(os.path.join(results, "matrix.jsonl")), key=scene_key)
    scaling = read_lines(os.path.join(results, "scaling.jsonl"))
    variants = read_lines(os.path.join(results, "variants.jsonl"))
    spheres = read_lines(os.path.join(results, "spheres.jsonl"))
    with open(os.path.join(results, "machine.json")) as f:
        machine = json.load(f)
    plot_triangles(spheres, matrix, os.path.join(results, "frame_time_vs_triangles.png"))
    plot_resolution(matrix, os.path.join(results, "frame_time_vs_resolution.png"))
    rel = os.path.relpath(results, os.path.dirname(output) or ".")

    first = matrix[0]
    load_note = (
        f"The 1-minute load average was {machine['load_before']:.2f} when the run started "
        f"({machine['load_after']:.2f} at its end, which counts the benchmark's own threads)"
    )
    if machine["load_before"] >= 0.5:
        load_note += (": other jobs were running on this 2-core machine, so the numbers are "
                      "noisier and slower than on an idle one")
    load_note += "."
    commit = machine["commit"] + (" plus uncommitted changes" if machine.get("dirty") else "")

    out = []
    w = out.append
    w("# Performance")
    w("")
    w("tessera's CPU renderer against Mesa's llvmpipe, on the same machine in the same run: "
      "`tessera bench --vs llvmpipe` draws every frame twice, once with tessera and once through "
      "OpenGL in an OSMesa context (llvmpipe), with the same triangles, camera matrices, lights, "
      "lighting model, back-face culling and depth test, at the same resolution and on the same "
      "number of threads (llvmpipe's `LP_NUM_THREADS` = tessera's `--workers`).")
    w("")
    w(f"Measured {machine['date']} at commit `{commit}`. The numbers change as the renderer "
      "gets faster: regenerate this page (numbers, plots and all) with one command, from the "
      "repository's root:")
    w("")
    w("```sh")
    w("bench/run_all.sh            # FRAMES=30 by default; MAX_LOAD=0.5 waits for an idle machine")
    w("```")
    w("")
    w("It builds `tessera` in Release, runs the commands below, keeps the raw JSON lines in "
      f"[`{rel}/`]({rel}/) and rewrites this file with `bench/report.py`.")
    w("")
    w("## Machine")
    w("")
    w("| | |")
    w("|---|---|")
    w(f"| CPU | {machine['cpu']} ({', '.join(machine['simd'])}) |")
    best = ("AVX-512" if "avx512f" in machine["simd"] else
            "AVX2 (this CPU has no AVX-512)" if "avx2" in machine["simd"] else "SSE2")
    w(f"| tessera's tile kernels | {best}, chosen at run time |")
    w(f"| cores | {machine['cores']} |")
    w(f"| compiler | {machine['compiler']} (CMake Release: -O3) |")
    w(f"| OpenGL reference | {first.get('reference', '?')}, {first.get('reference_version', '?')} |")
    w(f"| kernel | Linux {machine['kernel']} |")
    w(f"| frames | {machine['frames']} timed (after {first['warmup_frames']} untimed) per scene "
      "and resolution; the median is reported |")
    w("")
    w(load_note)
    w("")
    w("## Every scene at every resolution")
    w("")
    w(f"`tessera bench --json --vs llvmpipe --frames {machine['frames']}`: "
      f"{first['shading']} shading, back faces culled, {first['workers']} workers "
      f"(llvmpipe: LP_NUM_THREADS={first['workers']}). "
      "Ratio = llvmpipe time / tessera time: above 1, tessera is faster.")
    w("")
    w("| scene | what | triangles | resolution | tessera ms | llvmpipe ms | ratio |")
    w("|---|---|---:|---|---:|---:|---:|")
    for r in matrix:
        w(f"| {r['scene']} | {SCENE_WHAT.get(r['scene'], 'model file')} | {r['triangles']:,} | "
          f"{r['resolution']} | {ms(r['median_ms'])} | {ms(r['llvmpipe_median_ms'])} | "
          f"{r['ratio']:.2f} |")
    slower = [r for r in matrix if r["ratio"] < 1.0]
    w("")
    if slower:
        w("tessera is slower than llvmpipe on: " + ", ".join(
            f"{r['scene']} at {r['resolution']} ({r['ratio']:.2f})" for r in slower) + ".")
    else:
        w("tessera is faster than llvmpipe on every scene at every resolution.")
    w("")
    w(f"![frame time against triangle count]({rel}/frame_time_vs_triangles.png)")
    w("")
    w(f"![frame time against resolution]({rel}/frame_time_vs_resolution.png)")
    w("")
    w("## Triangle count: UV spheres at 1920x1080")
    w("")
    w("`bench/sphere_obj.py` writes spheres of 4k^2 triangles as OBJ files; each is timed with "
      "`tessera bench --json --vs llvmpipe --resolution 1920,1080 sphere_N.obj` (Gouraud, back "
      "faces culled: about half the triangles are drawn). The first plot above draws them.")
    w("")
    w("| triangles | tessera ms | llvmpipe ms | ratio |")
    w("|---:|---:|---:|---:|")
    for r in sorted(spheres, key=lambda r: r["triangles"]):
        w(f"| {r['triangles']:,} | {ms(r['median_ms'])} | {ms(r['llvmpipe_median_ms'])} | "
          f"{r['ratio']:.2f} |")
    w("")
    w("## Worker scaling: the bunny at 1920x1080")
    w("")
    w("`tessera bench --json --vs llvmpipe --resolution 1920,1080 --workers N bunny`, one "
      "process per N (llvmpipe reads LP_NUM_THREADS once per process).")
    w("")
    w("| workers | tessera ms | llvmpipe ms | ratio |")
    w("|---:|---:|---:|---:|")
    for r in sorted(scaling, key=lambda r: r["workers"]):
        w(f"| {r['workers']} | {ms(r['median_ms'])} | {ms(r['llvmpipe_median_ms'])} | "
          f"{r['ratio']:.2f} |")
    by_workers = {r["workers"]: r for r in scaling}
    if 1 in by_workers and 2 in by_workers:
        t = by_workers[1]["median_ms"] / by_workers[2]["median_ms"]
        g = by_workers[1]["llvmpipe_median_ms"] / by_workers[2]["llvmpipe_median_ms"]
        w("")
        w(f"Speed-up from 1 to 2 workers: tessera {t:.2f}x, llvmpipe {g:.2f}x.")
    w("")
    w("## The bunny at 1920x1080 with other shading and culling")
    w("")
    w("For comparison with the llvmpipe numbers in `/work/shared/REFERENCES.md` (16-21 ms "
      "Gouraud with back faces culled, 24 ms per-pixel lighting, 34 ms back faces drawn, on a "
      "2-core Zen 4).")
    w("")
    w("| shading | back faces | tessera ms | llvmpipe ms | ratio |")
    w("|---|---|---:|---:|---:|")
    base = next((r for r in matrix if r["scene"] == "bunny" and r["resolution"] == "1920x1080"),
                None)
    for r in ([base] if base else []) + variants:
        w(f"| {r['shading']} | {r['back_faces']} | {ms(r['median_ms'])} | {ms(r['llvmpipe_median_ms'])} | "
          f"{r['ratio']:.2f} |")
    w("")
    w("## What is measured")
    w("")
    w("- The timed loop covers rendering only: scenes are built and models loaded before it, "
      "llvmpipe's shaders are compiled and its vertex and index buffers uploaded once per scene, "
      "and nothing is encoded or written. The model turns 2 degrees about its up axis every "
      "frame (the fill scene about the view axis).")
    w("- tessera renders colour only (no depth, id or normal AOVs, no lines): clear, vertex, "
      "clip, setup, bin, raster, shade and the sRGB resolve into `Frame::color`.")
    w("- llvmpipe draws with GLSL 1.20 shaders that implement tessera's lighting (Lambert from "
      "directional lights plus ambient; Gouraud per vertex, smooth per fragment, flat from face "
      "normals in a de-indexed copy of the mesh) and encode sRGB in the fragment shader; indexed "
      "meshes use `glDrawElements` from VBOs; each frame ends with `glFinish()` before the clock "
      "stops. `tests/bench_test.cpp` checks that the two images agree (coverage and colour).")
    w("- The fill scene is drawn back to front, so llvmpipe shades every layer of every pixel "
      "(its early depth test cannot reject them), while tessera's visibility buffer shades each "
      "pixel once: this scene measures exactly that design difference.")
    w("- Micro-benchmarks of single stages and whole frames: `build/bench/tessera_microbench`.")
    w("")
    with open(output, "w") as f:
        f.write("\n".join(out))


if __name__ == "__main__":
    main()
