"""The outputs meant to be drawn, against independent numpy checks, on random volumes, label
maps and the paper's sphere:

* vtkStandardPlanePolyhedrizer TriangulatedFaces: triangles only, none flat, n - 2 per face
  whose StandardFaces loop has n pointels, each facing along its face's normal (its normal
  has a positive dot product with the plane normal: the face is drawn as a surface over its
  plane, no fold), closed (each edge used as often in both directions), and per face the
  same vector area as the face's surfels (both surfaces have the same boundary loop).
* SemiDiscrete: triangles only, none flat, facing along their normal, closed.
* vtkEVMBoundaryFilter Polygons: what VTK draws, the fan of triangles from each polygon's
  first point, covers each face exactly: every fan triangle faces outwards or is flat, and
  per face the fan's area equals the face's surfel count; closed; every corner of the
  Loops output is a corner of the pieces; no point of the output lies inside an edge of a
  Loops, Polygons or Triangles cell (no T-junction), in Labels mode between labels too
  (Triangles there: every loop corner is a corner of its face's triangles).

Coordinates are integers (voxel corners), so everything is compared exactly.
"""

import collections
import sys

import numpy as np
import voxelbrep
from voxelbrep_testing import Checker, cells, cell_array, make_image, points
from voxelbrep_testing import surfel_count

check = Checker("TestRenderedOutputs")


def corners_of(polydata):
    """Point coordinates as integers (the tests use unit spacing and origin 0, cell data)."""
    p = points(polydata)
    r = np.rint(p)
    assert np.allclose(p, r)
    return r.astype(np.int64)


def points_inside_edges(polydata):
    """Points of the output lying strictly inside an edge of one of its cells (T-junctions),
    by walking the lattice points of every edge."""
    corner = corners_of(polydata)
    present = set(map(tuple, corner.tolist()))
    found = 0
    for c in cells(polydata):
        for a, b in zip(c, list(c[1:]) + [c[0]]):
            d = corner[b] - corner[a]
            steps = int(np.gcd.reduce(np.abs(d)))
            for k in range(1, steps):
                found += tuple((corner[a] + d // steps * k).tolist()) in present
    return found


def directed_edge_balance(polys):
    """Edges used more often in one direction than in the other (0 for a closed surface)."""
    count = collections.Counter()
    for c in polys:
        for i in range(len(c)):
            count[(int(c[i]), int(c[(i + 1) % len(c)]))] += 1
    return sum(1 for (a, b), k in count.items() if count.get((b, a), 0) != k)


def updated_copy(f):
    """The filter's output after an update, copied (it outlives the filter)."""
    f.Update()
    result = f.GetOutput()
    copy = type(result)()
    copy.DeepCopy(result)
    return copy


def polyhedrizer(image, mode, labels=False):
    f = voxelbrep.vtkStandardPlanePolyhedrizer()
    f.SetInputData(image)
    f.GenerateReversionOff()
    if labels:
        f.SetSelectionModeToLabels()
    f.SetOutputMode(mode)
    return updated_copy(f)


def triangle_normals(corner, tris):
    p = corner[tris]
    return np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])  # twice the vector area


def check_triangles(tag, out):
    polys = cells(out)
    check.true(tag + ": triangles only", all(len(c) == 3 for c in polys))
    tris = np.array(polys, dtype=np.int64).reshape(-1, 3)
    corner = corners_of(out)
    twice = triangle_normals(corner, tris)
    normal = cell_array(out, "PlaneNormal").astype(np.int64)
    check.true(tag + ": no flat triangle", bool((np.abs(twice).sum(axis=1) > 0).all()))
    facing = np.einsum("ij,ij->i", twice, normal)
    check.equal(tag + ": triangles facing away from their plane's normal",
                int((facing <= 0).sum()), 0)
    check.equal(tag + ": edges not matched by an opposite edge", directed_edge_balance(polys), 0)
    return tris, twice


def check_polyhedrizer(tag, values, labels=False):
    image = make_image(values, cell_data=True)
    P = voxelbrep.vtkStandardPlanePolyhedrizer
    tri = polyhedrizer(image, P.TRIANGULATED_FACES, labels)
    loops = polyhedrizer(image, P.STANDARD_FACES, labels)
    surf = polyhedrizer(image, P.SURFELS, labels)
    semi = polyhedrizer(image, P.SEMI_DISCRETE, labels)
    binary = [values == k for k in np.unique(values) if k != 0] if labels else [values != 0]
    check.equal(tag + ": surfels", surf.GetNumberOfCells(), sum(surfel_count(b) for b in binary))
    _, twice = check_triangles(tag + " TriangulatedFaces", tri)
    face = cell_array(tri, "FaceId")
    loop_sizes = {int(f): len(c) for f, c in zip(cell_array(loops, "FaceId"), cells(loops))}
    per_face = collections.Counter(int(f) for f in face)
    check.equal(tag + ": faces with other than n - 2 triangles",
                sum(1 for f, n in loop_sizes.items() if per_face.get(f, 0) != n - 2), 0)
    # Vector areas per face: the triangles' against the surfels'.
    tri_area = np.zeros((len(loop_sizes), 3), dtype=np.int64)
    np.add.at(tri_area, face, twice)
    quads = np.array(cells(surf), dtype=np.int64)
    qc = corners_of(surf)[quads]
    quad_twice = np.cross(qc[:, 2] - qc[:, 0], qc[:, 3] - qc[:, 1])  # twice a quad's area
    surf_area = np.zeros_like(tri_area)
    np.add.at(surf_area, cell_array(surf, "FaceId"), quad_twice)
    check.equal(tag + ": faces whose triangles' vector area differs from their surfels'",
                int((tri_area != surf_area).any(axis=1).sum()), 0)
    check_triangles(tag + " SemiDiscrete", semi)


def evm(image, mode, labels=False, merge=False):
    f = voxelbrep.vtkEVMBoundaryFilter()
    f.SetInputData(image)
    if labels:
        f.SetSelectionModeToLabels()
    f.SetMergeNonManifoldFaces(merge)
    f.SetOutputMode(mode)
    return updated_copy(f)


def check_evm(tag, values, labels=False, merge=False, planar=False):
    image = make_image(values, cell_data=True)
    E = voxelbrep.vtkEVMBoundaryFilter
    pieces = evm(image, E.POLYGONS, labels, merge)
    loops = evm(image, E.LOOPS, labels, merge)
    surf = evm(image, E.SURFELS, labels, merge)
    polys = cells(pieces)
    corner = corners_of(pieces)
    faces = cell_array(pieces, "FaceId")
    # The fan VTK draws: (c0, ci, ci+1) for every polygon.
    fan, fan_face = [], []
    for f, c in zip(faces, polys):
        for i in range(1, len(c) - 1):
            fan.append((c[0], c[i], c[i + 1]))
            fan_face.append(f)
    fan = np.array(fan, dtype=np.int64).reshape(-1, 3)
    twice = triangle_normals(corner, fan)
    # The face's outward normal: the largest component of its pieces' vector area.
    face_count = int(faces.max()) + 1 if len(faces) else 0
    area = np.zeros((face_count, 3), dtype=np.int64)
    np.add.at(area, np.array(fan_face, dtype=np.int64), twice)
    normal_of_face = np.sign(area) * (np.abs(area) == np.abs(area).max(axis=1)[:, None])
    facing = np.einsum("ij,ij->i", twice, normal_of_face[np.array(fan_face, dtype=np.int64)])
    check.equal(tag + ": fan triangles facing inwards", int((facing < 0).sum()), 0)
    check.true(tag + ": every face planar along an axis",
               bool((np.abs(normal_of_face).sum(axis=1) == 1).all()))
    # Per face: the fan's area (twice) = 2 x its number of surfels.
    surf_per_face = np.zeros(face_count, dtype=np.int64)
    loops_faces = cell_array(loops, "FaceId")
    loop_hole = cell_array(loops, "LoopType")
    loop_corner = corners_of(loops)
    for f, hole, c in zip(loops_faces, loop_hole, cells(loops)):
        p = loop_corner[c]
        surf_per_face[f] += np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0).dot(
            normal_of_face[f])
    check.equal(tag + ": faces whose drawn area differs from their loops' area",
                int((np.abs(area).sum(axis=1) != surf_per_face).sum()), 0)
    if not planar:  # (a 2D image's surfels are pixel edges)
        check.equal(tag + ": total area = surfels", int(np.abs(area).sum()) // 2,
                    surf.GetNumberOfCells())
    if not planar:  # (a 2D image's faces have a border)
        check.equal(tag + ": edges not matched by an opposite edge",
                    directed_edge_balance(polys), 0)
    # Every loop corner is a corner of the face's pieces.
    piece_points = collections.defaultdict(set)
    for f, c in zip(faces, polys):
        piece_points[int(f)].update(tuple(corner[i]) for i in c)
    missing = 0
    for f, c in zip(loops_faces, cells(loops)):
        missing += sum(1 for i in c if tuple(loop_corner[i]) not in piece_points[int(f)])
    check.equal(tag + ": loop corners that are not corners of the pieces", missing, 0)
    triangles = evm(image, E.TRIANGLES, labels, merge)
    for name, out in (("Loops", loops), ("Polygons", pieces), ("Triangles", triangles)):
        if labels and name == "Triangles":
            # Two labels may cut their shared surface into faces differently: a corner of one
            # label's face can lie inside another label's face, and a diagonal of that face's
            # triangles through it. Along the loops the triangles keep every loop corner.
            check.equal(tag + ": loop corners that are not corners of the triangles",
                        loop_corners_missing(loops, out), 0)
            continue
        check.equal(tag + ": points inside edges (T-junctions) in " + name,
                    points_inside_edges(out), 0)


def loop_corners_missing(loops, out):
    """Corners of the Loops output that are not corners of `out`'s cells of the same face."""
    corner, loop_corner = corners_of(out), corners_of(loops)
    of_face = collections.defaultdict(set)
    for f, c in zip(cell_array(out, "FaceId"), cells(out)):
        of_face[int(f)].update(tuple(corner[i]) for i in c)
    return sum(1 for f, c in zip(cell_array(loops, "FaceId"), cells(loops))
               for i in c if tuple(loop_corner[i]) not in of_face[int(f)])


def sphere(n, r):
    g = np.indices((n, n, n)).astype(float) - (n - 1) / 2.0
    return ((g ** 2).sum(axis=0) <= r * r).astype(np.uint8)


def main():
    rng = np.random.default_rng(8)
    for trial in range(12):
        dims = tuple(int(d) for d in rng.integers(3, 9, size=3))
        density = [0.2, 0.5, 0.8][trial % 3]
        values = (rng.random(dims[::-1]) < density).astype(np.uint8)
        check_polyhedrizer("random %d" % trial, values)
        check_evm("random %d" % trial, values, merge=trial % 4 == 3)
    labels = rng.integers(0, 4, size=(6, 7, 8)).astype(np.uint8)
    check_polyhedrizer("labels", labels, labels=True)
    check_evm("labels", labels, labels=True)
    for trial in range(4):  # label maps of blocks: faces of different sizes meet
        blocks = rng.integers(0, 6, size=(3, 3, 3)).astype(np.uint8)
        sizes = [rng.integers(1, 4, size=3) for _ in range(3)]
        values = blocks.repeat(sizes[0], axis=0).repeat(sizes[1], axis=1).repeat(sizes[2], axis=2)
        values[rng.random(values.shape) < 0.1] = 0
        check_evm("label blocks %d" % trial, values, labels=True, merge=trial % 2 == 1)
    check_evm("2D labels", rng.integers(0, 4, size=(1, 9, 11)).astype(np.uint8), labels=True,
              planar=True)
    ball = sphere(25, 11.5)  # the paper's sphere
    check_polyhedrizer("sphere", ball)
    check_evm("sphere", ball)
    # A face with holes and concave faces: a plate with holes on a comb.
    plate = np.zeros((6, 12, 12), dtype=np.uint8)
    plate[1:3, 1:11, 1:11] = 1
    plate[1:3, 3:5, 3:5] = 0
    plate[1:3, 6:9, 4:9] = 0
    plate[3:5, 1:11, 1:11:2] = 1
    check_evm("plate", plate)
    for trial in range(6):  # 2D images: faces with holes inside holes
        image2d = (rng.random((1, 14, 13)) < 0.55).astype(np.uint8)
        check_evm("2D %d" % trial, image2d, merge=trial % 2 == 1, planar=True)
    check_polyhedrizer("plate", plate)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
