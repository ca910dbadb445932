#!/usr/bin/env python3
"""Prints the README's benchmark tables (Markdown) from a bench.json written by hemirad-bench.

    python3 bench/tables.py bench.json
"""
import json
import sys


def main(path):
    b = json.load(open(path))
    ex = {e["name"]: e for e in b["experiments"]}
    print("| experiment | polygons | leaf patches | shots | seconds | paper 002 (GeForce FX 5900) | goal here |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name in ("room402", "scene3138"):
        e = ex.get(name)
        if not e:
            continue
        goal = e.get("goal_seconds", 0)
        ok = "met" if e["seconds"] <= goal else "missed"
        print(f"| `{name}` | {e['polygons']} | {e['leaf_patches']:,} | {e['shots']} | "
              f"**{e['seconds']:.2f}** | {e.get('paper002_seconds', 0):.1f} s | "
              f"≤ {goal:.1f} s ({ok}) |")
    print()
    print("| Cornell box to a 1 % error bound | leaf patches | shots | seconds | error bound | stop |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name in ("cornell_hierarchical", "cornell_flat", "cornell_hemicube", "cornell_analytic"):
        e = ex.get(name)
        if e:
            print(f"| `{name}` | {e['leaf_patches']:,} | {e['shots']} | {e['seconds']:.2f} | "
                  f"{e['error_bound']:.3g} | {e.get('stop', '')} |")
    print()
    print("Per shot, ms (means, every hemicube of a shot: those of nodes whose children shoot "
          "instead too): select, push-pull, cull (CPU), render (rasterise + analytic shader), "
          "readback, reduce, update; peak memory of the experiment's process.")
    print()
    print("| experiment | polygons | leaf patches | ms/shot | select | push-pull | cull | render | readback | reduce | update | peak MiB |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for e in b["experiments"]:
        if "breakdown" not in e:  # accuracy, soak and mpi_scaling print their own figures
            continue
        bd, n = e["breakdown"], max(e["shots"], 1)
        ms = lambda k: 1000 * bd.get(k, 0) / n
        print(f"| `{e['name']}` | {e['polygons']} | {e['leaf_patches']:,} | "
              f"{1000 * e['seconds_per_shot']:.1f} | {ms('select'):.2f} | {ms('push_pull'):.2f} | "
              f"{ms('ff_cull'):.2f} | {ms('ff_render'):.1f} | {ms('ff_readback'):.2f} | {ms('ff_reduce'):.2f} | "
              f"{ms('update'):.2f} | {e.get('peak_rss_mib', 0):.0f} |")
    print()
    print(f"`shot_overhead_ratio` (whole shot ÷ bare hemicube render + readback at the same "
          f"resolution, same run): **{b['shot_overhead_ratio']:.3f}**")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench.json")
