#!/usr/bin/env python3
"""Dynamic-scene benchmark (issue 16; docs/dynamic.md): renders walking sequences with
`lumaslam synth`, runs `lumaslam run` on each with every removal configuration and several
seeds, and prints a Markdown table (ATE median and worst over the seeds, tracked frames, median
ms per frame from timing.csv, moving features per frame).

  scripts/bench-dynamic.py                       # every sequence and configuration
  scripts/bench-dynamic.py --sequences photo-walkers crate --configs none geometry
  scripts/bench-dynamic.py --seeds 1 2 --frames 100 --sequential

Mapping runs threaded (as users run it) unless --sequential. Datasets are cached in
--work (default build-bench-dynamic) and rendered again only when missing."""
import argparse
import csv
import json
import pathlib
import shutil
import statistics
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
PEOPLE = "data/labels/person_boxes.txt"
NIGHT = "data/llvip/night_people_sample"  # LLVIP night street people: VOC labels, visible images

# name: (preset, extra synth flags, what it shows)
SEQUENCES = {
    "walking-xyz": ("walking-xyz-rgbd", [], "procedural walkers and a moving crate"),
    "photo-walkers": ("walking-xyz-rgbd", ["--people-images", "{people}", "--moving-boxes", "0"],
                      "walkers cut from real person photos"),
    "photo-walkers-crate": ("walking-xyz-rgbd", ["--people-images", "{people}"],
                            "photo walkers and the crate (no COCO class)"),
    "night-people-crate": ("walking-xyz-rgbd",
                           ["--people-images", "{night}/Annotations",
                            "--people-image-folder", "{night}/visible/test",
                            "--people-image-folder", "{night}/visible/train"],
                           "walkers cut from LLVIP night street photos, and the crate"),
    "walking-rpy": ("walking-rpy-rgbd", ["--people-images", "{people}", "--moving-boxes", "0"],
                    "fast rotations, photo walkers"),
    "walking-halfsphere": ("walking-halfsphere-rgbd",
                           ["--people-images", "{people}", "--moving-boxes", "0"],
                           "half sphere, three photo walkers"),
    "walking-static": ("walking-static-rgbd", ["--people-images", "{people}", "--moving-boxes", "0"],
                       "still camera, photo walkers"),
    "sitting": ("sitting-xyz-rgbd", ["--people-images", "{people}"],
                "photo people sitting and shifting a few cm (the motion test must not hurt)"),
    "static": ("xyz-rgbd", [], "no people (the motion test must not hurt)"),
}

# name: (detector, motion evidence on)
CONFIGS = {
    "none": ("none", False),
    "geometry": ("none", True),
    "yolo": ("yolo", False),
    "yolo+geometry": ("yolo", True),
    "boxes": ("boxes", False),
}


def run(cmd, log):
    with open(log, "w") as out:
        result = subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(map(str, cmd))}; see {log}")


def dataset(args, name, seed):
    preset, flags, _ = SEQUENCES[name]
    folder = args.work / "data" / f"{name}-{args.frames}-s{seed}"
    if not (folder / "groundtruth.txt").exists():
        if folder.exists():
            shutil.rmtree(folder)
        paths = {"people": str(args.shared / PEOPLE), "night": str(args.shared / NIGHT)}
        cmd = [args.lumaslam, "synth", folder, "--preset", preset, "--frames", str(args.frames),
               "--seed", str(seed)] + [f.format(**paths) for f in flags]
        run(cmd, args.work / "synth.log")
    # YOLO knows no "box": a copy of the settings that removes people only.
    person_only = folder / "settings_person.yaml"
    if not person_only.exists():
        text = (folder / "settings.yaml").read_text().splitlines()
        text = [l for l in text if not l.startswith("Detector.classes")]
        person_only.write_text("\n".join(text + ['Detector.classes: "person"', ""]))
    return folder


def run_config(args, folder, config, seed):
    detector, geometry = CONFIGS[config]
    out = args.work / "runs" / f"{folder.name}-{config.replace('+', '-')}"
    settings = folder / "settings.yaml"
    if detector == "yolo":
        spec = f"yolo:{args.model}"
        settings = folder / "settings_person.yaml"
    elif detector == "boxes":
        spec = f"boxes:{folder / 'detections.txt'}"
    else:
        spec = "none"
    cmd = [args.lumaslam, "run", "--dataset", f"tum:{folder}", "--settings", settings,
           "--detector", spec, "--out", out]
    if not geometry:
        cmd.append("--no-motion-evidence")
    if args.sequential:
        cmd.append("--sequential")
    run(cmd, out.with_suffix(".log"))
    summary = json.loads((out / "summary.json").read_text())
    with open(out / "timing.csv") as f:
        rows = list(csv.DictReader(f))
    return {
        "ate": summary["evaluation"]["ate"]["rmse"],
        "tracked": summary["tracked"],
        "frames": summary["frames"],
        "ms": statistics.median(float(r["total_ms"]) for r in rows),
        "motion_ms": statistics.median(float(r.get("motion_ms") or 0) for r in rows),
        "moving": statistics.mean(float(r.get("moving_features") or 0) for r in rows),
        "dropped": statistics.mean(float(r["dropped_features"]) for r in rows),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lumaslam", type=pathlib.Path, default=ROOT / "build" / "lumaslam")
    parser.add_argument("--shared", type=pathlib.Path, default=ROOT.parent / "shared")
    parser.add_argument("--model", type=pathlib.Path, default=None,
                        help="YOLO model (default: SHARED/models/yolov5n-320.onnx)")
    parser.add_argument("--work", type=pathlib.Path, default=ROOT / "build-bench-dynamic")
    parser.add_argument("--sequences", nargs="+", default=list(SEQUENCES), choices=SEQUENCES)
    parser.add_argument("--configs", nargs="+", default=list(CONFIGS), choices=CONFIGS)
    parser.add_argument("--seeds", nargs="+", type=int, default=[1, 2, 3, 4, 5])
    parser.add_argument("--frames", type=int, default=150)
    parser.add_argument("--sequential", action="store_true", help="local mapping in one thread")
    args = parser.parse_args()
    args.model = args.model or args.shared / "models" / "yolov5n-320.onnx"
    args.work.mkdir(parents=True, exist_ok=True)
    (args.work / "runs").mkdir(exist_ok=True)

    mode = "sequential" if args.sequential else "threaded mapping"
    print(f"{args.frames} frames, seeds {' '.join(map(str, args.seeds))}, {mode}\n")
    print("| sequence | configuration | ATE median | ATE worst | tracked (min of runs) | "
          "ms/frame | motion test ms | moving / frame | dropped / frame |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name in args.sequences:
        folders = {seed: dataset(args, name, seed) for seed in args.seeds}
        for config in args.configs:
            results = [run_config(args, folders[seed], config, seed) for seed in args.seeds]
            ates = [r["ate"] for r in results]
            tracked = min(r["tracked"] for r in results)
            print(f"| {name} | {config} | {statistics.median(ates):.4f} m | {max(ates):.4f} m | "
                  f"{tracked}/{results[0]['frames']} | "
                  f"{statistics.median(r['ms'] for r in results):.1f} | "
                  f"{statistics.median(r['motion_ms'] for r in results):.2f} | "
                  f"{statistics.mean(r['moving'] for r in results):.0f} | "
                  f"{statistics.mean(r['dropped'] for r in results):.0f} |", flush=True)


if __name__ == "__main__":
    main()
