#!/usr/bin/env python3
"""How well the hybrid's probe picks each frame's way (--frame-way, src/hybrid/README.md).

For every scene the hybrid renders the same camera path three times in one run: every frame by
local z-buffering (--frame-way local), every frame cast every pixel (rays), and as the probe
chooses (auto). Per frame (after the first): both ways' times, the probe's counts (the pixels its
plane would finish, the triangles in front of it, a near triangle's cost in rays) and its choice;
per scene: the share of frames it chose the faster way and what the wrong choices cost.

Usage: python3 runs/peers/frame_way.py [--quick]   (from the repository root, after
       scripts/build.sh and scripts/fetch-test-meshes.sh; about 5 minutes)
Writes runs/peers/frame_way.csv.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import common  # noqa: E402

common.accept_args(flags=("--quick",))

HERE = os.path.dirname(os.path.abspath(__file__))
ARMADILLO = os.path.join(common.DATA, "armadillo.off")
# name: (scene, width, height, frames)
SCENES = {
    "city_paper": ("builtin:city?blocks=12", 512, 512, 16),
    "city_1080p": ("builtin:city?blocks=12", 1920, 1080, 8),
    "forest": ("builtin:forest", 640, 480, 8),
    "armadillo": (ARMADILLO, 640, 480, 10),
    "landscape_1e6": ("builtin:landscape?objects=40000", 640, 480, 6),
    "landscape_1e7": ("builtin:landscape?objects=400000", 640, 480, 4),
}


def main():
    rows, commands = [], []
    for name, (scene, w, h, frames) in SCENES.items():
        if "--quick" in sys.argv:
            frames = 3
        runs = {}
        for way in ("auto", "local", "rays"):
            shown, rep = common.render(scene, ["--method", "hybrid", "--frame-way", way, "--frames",
                                               str(frames), "--width", str(w), "--height", str(h)],
                                       threads=common.CORES)
            commands.append(shown)
            runs[way] = rep["frames"]
        for i in range(1, frames):  # the first frame pays the set-up's page faults
            probe = runs["auto"][i]["counts"]
            local_s, rays_s = runs["local"][i]["seconds"], runs["rays"][i]["seconds"]
            chose_rays = probe.get("every_pixel_cast", 0.0) == 1.0
            rows.append({"scene": name, "frame": i, "width": w, "height": h,
                         "local_ms": round(1000 * local_s, 2), "rays_ms": round(1000 * rays_s, 2),
                         "auto_ms": round(1000 * runs["auto"][i]["seconds"], 2),
                         "chose": "rays" if chose_rays else "local",
                         "faster": "rays" if rays_s < local_s else "local",
                         "lost_ms": round(1000 * max(0.0, (rays_s if chose_rays else local_s)
                                                     - min(rays_s, local_s)), 2),
                         "finished_pixels": probe.get("probe_finished_pixels", ""),
                         "triangles": probe.get("probe_triangles", ""),
                         "near_triangle_cost": probe.get("probe_near_triangle_cost", ""),
                         "sampled_unit": probe.get("probe_sampled_unit", "")})
        mine = [r for r in rows if r["scene"] == name]
        right = sum(r["chose"] == r["faster"] for r in mine)
        print(f"{name}: the faster way in {right}/{len(mine)} frames, "
              f"{sum(r['lost_ms'] for r in mine):.1f} ms lost; local "
              f"{common.median(r['local_ms'] for r in mine):.1f}, rays "
              f"{common.median(r['rays_ms'] for r in mine):.1f}, auto "
              f"{common.median(r['auto_ms'] for r in mine):.1f} ms (medians)", flush=True)
    common.write_csv(os.path.join(HERE, "frame_way.csv"), rows, list(rows[0]), commands)


if __name__ == "__main__":
    main()
