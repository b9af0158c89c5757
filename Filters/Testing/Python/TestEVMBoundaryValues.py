"""vtkEVMBoundaryFilter on small numpy-built 3D images, checked against independent numpy /
scipy references:

* NumberOfVoxels, NumberOfSurfels (0/1 transitions of the padded mask),
  NumberOfExtremeVertices (XOR of the 8 shifted padded masks), NumberOfFaces and
  NumberOfHoles (components of each plane of equally oriented voxel faces, scipy.ndimage);
* total area of the Polygons / Triangles / Surfels / Polylines output (Newell areas of the
  loops, holes subtracted; vtkMassProperties for Triangles) = boundary faces x face area,
  with anisotropic spacing, non-zero origin and extent;
* enclosed volume by the divergence theorem = voxels x voxel volume (checks orientation);
* every directed edge of the triangles has its reverse (closed, consistently oriented);
* placement: point scalars put the surface half a spacing outside the selected point
  centres, cell scalars exactly on the selected cells' bounds; a direction matrix rotates
  the output;
* Labels and Range selection modes.
"""

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import voxelbrep_testing as vt  # noqa: E402

import voxelbrep  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkMassProperties  # noqa: E402

check = vt.Checker("TestEVMBoundaryValues")

MODES = vt.evm_output_modes()


def run_filter(image, mode, merge=False, selection="positive", lower=1.0, upper=1e300):
    f = voxelbrep.vtkEVMBoundaryFilter()
    f.SetInputData(image)
    f.SetOutputMode(MODES[mode])
    f.SetMergeNonManifoldFaces(merge)
    if selection == "labels":
        f.SetSelectionModeToLabels()
    elif selection == "range":
        f.SetSelectionModeToRange()
        f.SetLowerThreshold(lower)
        f.SetUpperThreshold(upper)
    f.Update()
    return f.GetOutput()


def measure(output, mode):
    """Area and enclosed volume of the output's cells (holes count negative)."""
    pts = vt.points(output)
    area = 0.0
    volume = 0.0
    loop_type = vt.cell_array(output, "LoopType")
    for c, ids in enumerate(vt.cells(output)):
        p = pts[vt.open_loop(ids)]
        n = vt.vector_area(p)
        if mode == "Polylines":
            # Lines carry no orientation rule of their own: use the loop type.
            area += (-1.0 if loop_type[c] == 1 else 1.0) * np.linalg.norm(n)
        else:
            # Holes run the other way round, so their Newell vectors point inwards; the
            # area of a face is the outer loop's area minus its holes'.
            area += (-1.0 if loop_type[c] == 1 else 1.0) * np.linalg.norm(n)
            volume += np.dot(p[0], n) / 3.0
    return area, volume


def directed_edges_balanced(output):
    edges = {}
    for ids in vt.cells(output):
        for a, b in zip(ids, np.roll(ids, -1)):
            edges[(a, b)] = edges.get((a, b), 0) + 1
    return all(edges.get((b, a), 0) == n for (a, b), n in edges.items())


def check_case(name, values, mask_of, spacing, origin, index_min, cell_data, selection="positive",
               lower=1.0, upper=1e300, direction=None):
    """Runs every output mode on one image and checks it against the references."""
    image = vt.make_image(values, spacing, origin, index_min, cell_data, direction=direction)
    masks = mask_of(values)  # {label: mask}
    voxel_volume = float(np.prod(spacing))
    expected = {
        "voxels": sum(int(m.sum()) for m in masks.values()),
        "surfels": sum(sum(vt.boundary_faces(m)) for m in masks.values()),
        "ev": sum(vt.extreme_vertices(m) for m in masks.values()),
        "area": sum(vt.boundary_area(m, spacing) for m in masks.values()),
    }
    expected["volume"] = expected["voxels"] * voxel_volume

    # Bounds of the selection in index space, then in world space.
    union = np.zeros(values.shape, bool)
    for m in masks.values():
        union |= m
    zz, yy, xx = np.nonzero(union)
    lo = np.array([xx.min(), yy.min(), zz.min()], float) + index_min
    hi = np.array([xx.max(), yy.max(), zz.max()], float) + index_min
    if cell_data:
        hi += 1.0  # cell i spans points i and i + 1
    else:
        lo -= 0.5  # point i is the centre of a voxel one spacing wide
        hi += 0.5
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                        for z in (lo[2], hi[2])])
    rot = np.eye(3) if direction is None else np.asarray(direction, float).reshape(3, 3)
    world = (rot @ (corners * spacing).T).T + origin
    expected_bounds = np.ravel(list(zip(world.min(axis=0), world.max(axis=0))))

    for merge in (False, True):
        fh = [vt.faces_and_holes_3d(m, merge) for m in masks.values()]
        expected_faces = sum(f for f, _ in fh)
        expected_holes = sum(h for _, h in fh)
        for mode in MODES:
            tag = "%s [%s, %s data, merge %s]" % (name, mode, "cell" if cell_data else "point",
                                                 merge)
            out = run_filter(image, mode, merge, selection, lower, upper)
            check.equal(tag + " NumberOfVoxels", vt.field_value(out, "NumberOfVoxels"),
                        expected["voxels"])
            check.equal(tag + " NumberOfSurfels", vt.field_value(out, "NumberOfSurfels"),
                        expected["surfels"])
            check.equal(tag + " NumberOfExtremeVertices",
                        vt.field_value(out, "NumberOfExtremeVertices"), expected["ev"])
            check.true(tag + " has cells", out.GetNumberOfCells() > 0)
            check.close(tag + " bounds", np.array(out.GetBounds()), expected_bounds)
            area, volume = measure(out, mode)
            check.close(tag + " area", area, expected["area"])
            if mode != "Polylines":
                check.close(tag + " enclosed volume", volume, expected["volume"])
            labels = vt.cell_array(out, "Label")
            if selection == "labels":
                check.equal(tag + " Label values", sorted(set(labels.tolist())),
                            sorted(masks.keys()))
                # Per label: the cells of each label enclose exactly that label's voxels.
                if mode == "Triangles":
                    pts = vt.points(out)
                    all_cells = vt.cells(out)
                    for lab, m in masks.items():
                        v = sum(np.dot(pts[ids[0]], vt.vector_area(pts[ids])) / 3.0
                                for c, ids in enumerate(all_cells) if labels[c] == lab)
                        check.close(tag + " volume of label %d" % lab, v,
                                    m.sum() * voxel_volume)
            else:
                check.true(tag + " Label is 1", bool(np.all(labels == 1)))
            if mode == "Surfels":
                check.equal(tag + " one cell per surfel", out.GetNumberOfCells(),
                            expected["surfels"])
                continue
            check.equal(tag + " NumberOfFaces", vt.field_value(out, "NumberOfFaces"),
                        expected_faces)
            check.equal(tag + " NumberOfHoles", vt.field_value(out, "NumberOfHoles"),
                        expected_holes)
            face_ids = vt.cell_array(out, "FaceId")
            check.equal(tag + " distinct FaceId", len(set(face_ids.tolist())), expected_faces)
            if mode in ("Loops", "Polylines"):
                loop_type = vt.cell_array(out, "LoopType")
                check.equal(tag + " hole loops", int(np.count_nonzero(loop_type == 1)),
                            expected_holes)
                check.equal(tag + " outer loops", int(np.count_nonzero(loop_type == 0)),
                            expected_faces)
            if mode == "Triangles":
                check.true(tag + " triangles only",
                           all(len(ids) == 3 for ids in vt.cells(out)))
                check.true(tag + " closed and consistently oriented",
                           directed_edges_balanced(out))
                if direction is None and selection != "labels":
                    mp = vtkMassProperties()
                    mp.SetInputData(out)
                    mp.Update()
                    check.close(tag + " vtkMassProperties area", mp.GetSurfaceArea(),
                                expected["area"], rtol=1e-6)
                    check.close(tag + " vtkMassProperties volume", mp.GetVolume(),
                                expected["volume"], rtol=1e-6)
            if mode == "Polygons":
                check.true(tag + " Polygons closed and consistently oriented",
                           directed_edges_balanced(out))
            if mode == "Polylines":
                check.equal(tag + " lines only", out.GetNumberOfLines(), out.GetNumberOfCells())


def positive(values):
    return {1: values > 0}


def main():
    rng = np.random.default_rng(20240601)
    spacing = (0.5, 1.25, 2.0)
    origin = (-3.0, 1.5, 7.0)
    index_min = (2, -3, 5)

    # A solid with a tunnel, a closed cavity holding a ball, and a second block touching it
    # along an edge only (non-manifold).
    solid = np.zeros((9, 10, 12), np.uint8)
    solid[1:8, 1:8, 1:8] = 1
    solid[3:6, 3:6, 1:8] = 0  # tunnel along x (holes in two faces)
    solid[1:8, 3:6, 3:6] = 0  # a second tunnel crossing it
    solid[8, 8:10, 8:12] = 1  # a bar touching the solid along an edge
    check_case("tunnels", solid, positive, spacing, origin, index_min, cell_data=False)
    check_case("tunnels", solid, positive, spacing, origin, index_min, cell_data=True)

    shell = np.zeros((8, 8, 8), np.uint8)
    shell[1:7, 1:7, 1:7] = 3
    shell[2:6, 2:6, 2:6] = 0  # cavity
    shell[3:5, 3:5, 3:5] = 2  # ball in the cavity
    check_case("nested shells", shell, positive, spacing, origin, index_min, cell_data=False)

    # Random voxels: many non-manifold edges and vertices.
    for seed in range(3):
        values = (rng.random((5, 6, 7)) < 0.45).astype(np.uint8)
        check_case("random %d" % seed, values, positive, spacing, origin, index_min,
                   cell_data=bool(seed % 2))

    # Labels: every non-zero value its own object.
    labels = rng.integers(0, 4, size=(5, 6, 7)).astype(np.uint8)
    labels[labels == 3] = 0
    check_case("labels", labels, lambda v: {int(k): v == k for k in np.unique(v) if k != 0},
               spacing, origin, index_min, cell_data=False, selection="labels")

    # Range on signed values, cell data.
    signed = rng.integers(-5, 6, size=(4, 5, 6)).astype(np.int16)
    check_case("range", signed, lambda v: {1: (v >= -2) & (v <= 1)}, spacing, origin,
               index_min, cell_data=True, selection="range", lower=-2, upper=1)
    floats = rng.normal(size=(4, 5, 6)).astype(np.float32)
    check_case("float range", floats, lambda v: {1: (v >= 0.25) & (v <= 1.5)}, spacing,
               origin, index_min, cell_data=False, selection="range", lower=0.25, upper=1.5)

    # A direction matrix (rotation by 90 degrees about z): area and volume unchanged, the
    # bounds follow the rotated box.
    rotation = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
    check_case("rotated", solid, positive, spacing, origin, index_min, cell_data=False,
               direction=rotation)

    # Empty selection: no cells, zero counts, no error.
    f = voxelbrep.vtkEVMBoundaryFilter()
    f.SetInputData(vt.make_image(np.zeros((3, 3, 3), np.uint8)))
    f.Update()
    check.equal("empty selection cells", f.GetOutput().GetNumberOfCells(), 0)

    check.finish()


if __name__ == "__main__":
    main()
