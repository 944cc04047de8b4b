#!/usr/bin/env python3
"""Map the first frames of an RGB-D sequence, save the map, then localize the rest in it.

    PYTHONPATH=build/python python3 examples/python/localize_second_half.py \
        ../shared/data/7scenes_redkitchen/settings.yaml tum:../shared/data/7scenes_redkitchen 250

Prints the mapping run's ATE, how many later frames localized (and where tracking was lost),
and their error in the mapping run's alignment to the ground truth: the localized poses are
in the map's world, so the alignment found for the mapping frames is applied to them as is.
"""
import argparse
import os
import tempfile
import time

import numpy as np

import lumaslam


def track(system, spec, first, last=None):
    results = []
    for i, frame in enumerate(lumaslam.Dataset(spec, max_frames=last)):
        if i >= first:
            results.append(system.track_rgbd(frame.image, frame.depth, frame.timestamp))
    return results


def rigid_alignment(estimate, truth):
    """R, t minimising |R e + t - g| over matched positions (Umeyama without scale)."""
    ce, cg = estimate.mean(0), truth.mean(0)
    U, _, Vt = np.linalg.svd((truth - cg).T @ (estimate - ce))
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))])
    R = U @ D @ Vt
    return R, cg - R @ ce


def matched_positions(trajectory, ground_truth):
    truth = {round(t, 4): T[:3, 3] for t, T in zip(*ground_truth)}
    pairs = [(T[:3, 3], truth[round(t, 4)]) for t, T in zip(*trajectory) if round(t, 4) in truth]
    return np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])


def runs_of(results, offset):
    runs = []
    for r in results:
        ok = r.state == lumaslam.TrackState.TRACKING
        if runs and runs[-1][0] == ok:
            runs[-1][2] = r.frame
        else:
            runs.append([ok, r.frame, r.frame])
    return " ".join(f"{'tracked' if ok else 'lost'} {a + offset}-{b + offset}" for ok, a, b in runs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("settings")
    parser.add_argument("dataset", help="e.g. tum:PATH")
    parser.add_argument("split", type=int, help="frames [0, split) are mapped, the rest localized")
    args = parser.parse_args()
    ground_truth = lumaslam.Dataset(args.dataset).ground_truth()

    with tempfile.TemporaryDirectory() as tmp:
        map_file = os.path.join(tmp, "first.lmap")
        mapping = lumaslam.System(args.settings)
        track(mapping, args.dataset, 0, args.split)
        start = time.perf_counter()
        mapping.save_map(map_file)
        save_ms = 1000 * (time.perf_counter() - start)
        mapped = mapping.trajectory()
        keyframes = mapping.keyframe_count
        size_mb = os.path.getsize(map_file) / 1e6

        localizing = lumaslam.System(args.settings)
        start = time.perf_counter()
        localizing.load_map(map_file)
        load_ms = 1000 * (time.perf_counter() - start)
    localizing.set_localization_mode(True)
    results = track(localizing, args.dataset, args.split)
    localizing.shutdown()

    R, t = rigid_alignment(*matched_positions(mapped, ground_truth))
    estimate, truth = matched_positions(localizing.trajectory(), ground_truth)
    errors = np.linalg.norm(estimate @ R.T + t - truth, axis=1) if len(estimate) else np.zeros(1)
    localized = sum(r.state == lumaslam.TrackState.TRACKING for r in results)
    ate = lumaslam.evaluate(mapped, ground_truth)["ate"]["rmse"]
    print(f"mapped frames 0-{args.split - 1}: {len(mapped[0])} tracked, ATE {100 * ate:.2f} cm, "
          f"{keyframes} keyframes; map {size_mb:.1f} MB, saved in {save_ms:.0f} ms, "
          f"loaded in {load_ms:.0f} ms")
    print(f"localized {localized}/{len(results)} later frames ({runs_of(results, args.split)}), "
          f"{localizing.keyframe_count - keyframes} keyframes added, error in the mapping run's "
          f"alignment: rmse {100 * np.sqrt(np.mean(errors ** 2)):.2f} cm")


if __name__ == "__main__":
    main()
