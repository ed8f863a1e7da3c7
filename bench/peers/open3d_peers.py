#!/usr/bin/env python3
"""The Open3D peers of the equal-budget benchmark (bench/run_peers.sh), benchmark-only.

  open3d_peers.py poisson CLOUD OUT.ply [--depth D] [--crop Q] [--knn K]
      screened Poisson (create_from_point_cloud_poisson at octree depth D, default 9) from
      normals estimated on the K nearest points (default 30) and oriented consistently
      (orient_normals_consistent_tangent_plane, K); then the vertices whose density is below the
      Q quantile (default 0.01) are removed, as is usual, with their triangles.
  open3d_peers.py decimate MESH N OUT.ply
      quadric decimation (simplify_quadric_decimation) to 2N triangles, about N vertices;
      unreferenced vertices removed.

Every output is a PLY mesh; one line on stderr gives its vertices and triangles.
Debian's python3-open3d (0.16) and python3-numpy; run with Debian's /usr/bin/python3.
"""
import argparse
import sys

import numpy as np
import open3d as o3d


def poisson(args):
    pcd = o3d.io.read_point_cloud(args.cloud)
    if len(pcd.points) == 0:
        sys.exit(f"{args.cloud}: no points")
    pcd.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(knn=args.knn))
    pcd.orient_normals_consistent_tangent_plane(args.knn)
    mesh, densities = o3d.geometry.TriangleMesh.create_from_point_cloud_poisson(pcd, depth=args.depth)
    densities = np.asarray(densities)
    mesh.remove_vertices_by_mask(densities < np.quantile(densities, args.crop))
    mesh.remove_unreferenced_vertices()
    write(mesh, args.out)


def decimate(args):
    mesh = o3d.io.read_triangle_mesh(args.mesh)
    if len(mesh.triangles) == 0:
        sys.exit(f"{args.mesh}: no triangles")
    mesh = mesh.simplify_quadric_decimation(target_number_of_triangles=2 * args.n)
    mesh.remove_unreferenced_vertices()
    write(mesh, args.out)


def write(mesh, path):
    mesh.vertex_normals = o3d.utility.Vector3dVector()  # positions and triangles only
    if not o3d.io.write_triangle_mesh(path, mesh, write_ascii=False, compressed=False):
        sys.exit(f"{path}: cannot write")
    print(f"{path}: {len(mesh.vertices)} vertices, {len(mesh.triangles)} triangles", file=sys.stderr)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("poisson")
    p.add_argument("cloud")
    p.add_argument("out")
    p.add_argument("--depth", type=int, default=9)
    p.add_argument("--crop", type=float, default=0.01)
    p.add_argument("--knn", type=int, default=30)
    p.set_defaults(run=poisson)
    d = sub.add_parser("decimate")
    d.add_argument("mesh")
    d.add_argument("n", type=int)
    d.add_argument("out")
    d.set_defaults(run=decimate)
    args = parser.parse_args()
    o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
    args.run(args)


if __name__ == "__main__":
    main()
