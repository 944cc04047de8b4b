"""The Python module `lumaslam` (python/) on a synthetic RGB-D sequence with ground truth.

Run by ctest with PYTHONPATH at the built module and LUMASLAM_CLI at the `lumaslam` binary,
which writes the sequence (`lumaslam synth`) and the reference trajectory (`lumaslam run`).
"""
import os
import subprocess
import tempfile
import threading
import time
import unittest

import numpy as np

import lumaslam

CLI = os.environ["LUMASLAM_CLI"]
FRAMES = 120


def cli(*args):
    done = subprocess.run([CLI, *args], capture_output=True, text=True)
    if done.returncode != 0:
        raise AssertionError(f"lumaslam {' '.join(args)} failed:\n{done.stdout}{done.stderr}")


def read_tum(path):
    """A TUM trajectory file as (timestamps, 4x4 poses)."""
    rows = np.loadtxt(path, comments="#", ndmin=2)
    poses = np.repeat(np.eye(4)[None], len(rows), axis=0)
    for pose, (_, x, y, z, qx, qy, qz, qw) in zip(poses, rows):
        pose[:3, :3] = [
            [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
            [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
            [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)],
        ]
        pose[:3, 3] = [x, y, z]
    return rows[:, 0], poses


class Bindings(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="lumaslam_python_")
        cls.seq = os.path.join(cls.tmp.name, "seq")
        cli("synth", "--preset", "xyz-rgbd", "--frames", str(FRAMES), "--seed", "1", cls.seq)
        cls.settings = os.path.join(cls.seq, "settings.yaml")
        cls.spec = "tum:" + cls.seq

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def track_sequence(self, system, max_frames=None):
        results = []
        for frame in lumaslam.Dataset(self.spec, max_frames=max_frames):
            results.append(system.track_rgbd(frame.image, frame.depth, frame.timestamp))
        return results

    def test_tracks_within_one_centimetre(self):
        with lumaslam.System(self.settings, sequential=True) as system:
            results = self.track_sequence(system)
        self.assertEqual([r.frame for r in results], list(range(FRAMES)))
        tracked = [r for r in results if r.state == lumaslam.TrackState.TRACKING]
        self.assertGreaterEqual(len(tracked), 0.95 * FRAMES)
        for r in tracked:
            self.assertEqual(r.T_w_c.shape, (4, 4))
            self.assertEqual(r.T_w_c.dtype, np.float64)
            np.testing.assert_allclose(r.T_w_c[3], [0, 0, 0, 1])
        timestamps, poses = system.trajectory()
        self.assertEqual(poses.shape, (len(tracked), 4, 4))
        errors = lumaslam.evaluate((timestamps, poses),
                                   lumaslam.Dataset(self.spec).ground_truth())
        self.assertLessEqual(errors["ate"]["rmse"], 0.01)
        self.assertGreaterEqual(errors["coverage"], 0.95)
        self.assertGreater(system.keyframe_count, 0)

    def test_matches_the_cli_trajectory_in_sequential_mode(self):
        out = os.path.join(self.tmp.name, "cli")
        cli("run", "--dataset", self.spec, "--sequential", "--out", out)
        cli_times, cli_poses = read_tum(os.path.join(out, "trajectory.txt"))
        system = lumaslam.System(self.settings, sequential=True)
        self.track_sequence(system)
        system.shutdown()
        times, poses = system.trajectory()
        self.assertEqual(poses.shape, cli_poses.shape)
        np.testing.assert_allclose(times, cli_times, atol=1e-6, rtol=0)
        np.testing.assert_allclose(poses, cli_poses, atol=1e-9, rtol=0)

    def test_other_python_threads_run_while_a_frame_is_tracked(self):
        # With the GIL held through a call, another Python thread could run only between
        # calls (at most once per call); released, it ticks all through each call.
        system = lumaslam.System(self.settings, sequential=True)
        ticks, calls = [], []
        stop = threading.Event()

        def tick():
            while not stop.is_set():
                ticks.append(time.perf_counter())
                stop.wait(0.0005)

        ticker = threading.Thread(target=tick)
        ticker.start()
        try:
            for frame in lumaslam.Dataset(self.spec, max_frames=30):
                start = time.perf_counter()
                system.track_rgbd(frame.image, frame.depth, frame.timestamp)
                calls.append((start, time.perf_counter()))
        finally:
            stop.set()
            ticker.join()
        inside = sum(any(a < t < b for a, b in calls) for t in ticks)
        self.assertGreaterEqual(inside, 3 * len(calls), f"{inside} ticks in {len(calls)} calls")

    def test_bad_input_raises_with_a_message(self):
        system = lumaslam.System(self.settings, sequential=True)
        frame = next(iter(lumaslam.Dataset(self.spec, max_frames=1)))
        with self.assertRaisesRegex(TypeError, "depth: expected dtype uint16"):
            system.track_rgbd(frame.image, frame.depth.astype(np.int32), frame.timestamp)
        with self.assertRaisesRegex(ValueError, r"image: expected an HxW .* got shape \(4,\)"):
            system.track_rgbd(np.zeros(4, np.uint8), frame.depth, frame.timestamp)
        with self.assertRaisesRegex(RuntimeError, "trackMonocular.*rgbd"):
            system.track_monocular(frame.image, frame.timestamp)
        system.track_rgbd(frame.image, frame.depth, frame.timestamp)
        with self.assertRaisesRegex(RuntimeError, "not after the last one"):
            system.track_rgbd(frame.image, frame.depth, frame.timestamp)
        with self.assertRaisesRegex(RuntimeError, "missing.yaml"):
            lumaslam.System(os.path.join(self.tmp.name, "missing.yaml"))
        with self.assertRaisesRegex(ValueError, "alignment"):
            lumaslam.evaluate(system.trajectory(), system.trajectory(), alignment="se2")

    def test_save_load_and_localize(self):
        map_file = os.path.join(self.tmp.name, "room.lmap")
        mapping = lumaslam.System(self.settings, sequential=True)
        self.track_sequence(mapping)
        mapping.save_map(map_file)
        keyframes = mapping.keyframe_count
        localizing = lumaslam.System(self.settings, sequential=True)
        localizing.load_map(map_file)
        localizing.set_localization_mode(True)
        self.assertTrue(localizing.localization_mode)
        results = self.track_sequence(localizing)
        tracked = sum(r.state == lumaslam.TrackState.TRACKING for r in results)
        self.assertGreaterEqual(tracked, 0.95 * FRAMES)
        self.assertEqual(localizing.keyframe_count, keyframes)


if __name__ == "__main__":
    unittest.main()
