"""vtkStandardPlanePolyhedrizer against independent numpy checks: the surfels counted voxel by
voxel, every surfel's corners inside its face's standard plane (evaluated here in integer
corner coordinates recovered from the world points), surfel normals along the plane normal,
the per-face surfel counts, and the reversion equal to the selection. Random volumes, the
paper's sphere, label maps, point and cell scalars with origin, spacing and extent not at 0.
"""

import numpy as np
import voxelbrep
from voxelbrep_testing import Checker, cells, field_value, cell_array, make_image, points
from voxelbrep_testing import surfel_count
from vtkmodules.util import numpy_support as ns

check = Checker("TestStandardPlanePolyhedrizer")


def corner_index(world, spacing, origin, index_min, cell_data):
    """Corner coordinates of the image's voxel grid: voxel i spans corners i and i + 1."""
    shift = 0.0 if cell_data else -0.5  # point data: voxel i is centred on point i
    index = (world - np.asarray(origin)) / np.asarray(spacing) - np.asarray(index_min) - shift
    rounded = np.rint(index)
    check.true("points on voxel corners", bool(np.allclose(index, rounded, atol=1e-6)))
    return rounded.astype(np.int64)


def run(filter_, mode):
    filter_.SetOutputMode(mode)
    filter_.Update()
    return filter_.GetOutput()


def check_case(tag, mask, selected=None, spacing=(1, 1, 1), origin=(0, 0, 0),
               index_min=(0, 0, 0), cell_data=False, labels=False):
    values = mask if selected is None else selected
    image = make_image(values, spacing, origin, index_min, cell_data)
    f = voxelbrep.vtkStandardPlanePolyhedrizer()
    f.SetInputData(image)
    if labels:
        f.SetSelectionModeToLabels()
    binary = (values != 0) if labels else (mask != 0)
    surfels = run(f, f.SURFELS)
    expected_surfels = surfel_count(binary) if not labels else sum(
        surfel_count(values == k) for k in np.unique(values) if k != 0)
    check.equal(tag + ": one quad per surfel", surfels.GetNumberOfCells(), expected_surfels)
    check.equal(tag + ": NumberOfSurfels", field_value(surfels, "NumberOfSurfels"),
                expected_surfels)
    faces = field_value(surfels, "NumberOfFaces")
    if expected_surfels:
        corners = corner_index(points(surfels), spacing, origin, index_min, cell_data)
        quads = np.array(cells(surfels))
        p = corners[quads]  # (cells, 4, 3)
        normal = cell_array(surfels, "PlaneNormal").astype(np.int64)
        mu = cell_array(surfels, "PlaneOffset").astype(np.int64)
        value = np.einsum("cij,cj->ci", p, normal)
        omega = np.abs(normal).sum(axis=1)
        inside = (value >= mu[:, None]) & (value < (mu + omega)[:, None])
        check.true(tag + ": every surfel corner in its face's standard plane", bool(inside.all()))
        quad_normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 1])
        if np.prod(np.sign(spacing)) < 0:
            quad_normal = -quad_normal
        check.true(tag + ": surfels face along their plane's normal",
                   bool((np.einsum("ij,ij->i", quad_normal, normal) > 0).all()))
        ids = cell_array(surfels, "FaceId")
        sizes = cell_array(surfels, "SurfelCount")
        check.equal(tag + ": distinct FaceIds", len(np.unique(ids)), faces)
        check.true(tag + ": SurfelCount is the face's number of quads",
                   bool((np.bincount(ids)[ids] == sizes).all()))
    standard = run(f, f.STANDARD_FACES)
    check.equal(tag + ": one polygon per face", standard.GetNumberOfCells(), faces)
    check.equal(tag + ": SurfelCount sums to the surfels",
                int(cell_array(standard, "SurfelCount").sum()) if faces else 0, expected_surfels)
    if faces:
        corners = corner_index(points(standard), spacing, origin, index_min, cell_data)
        normal = cell_array(standard, "PlaneNormal").astype(np.int64)
        mu = cell_array(standard, "PlaneOffset").astype(np.int64)
        ok = True
        for c, loop in enumerate(cells(standard)):
            v = corners[loop] @ normal[c]
            ok = ok and bool(((v >= mu[c]) & (v < mu[c] + np.abs(normal[c]).sum())).all())
        check.true(tag + ": loops in their planes", ok)
    # The companion filter, from the standard faces alone (through a deep copy, as a file
    # read back would give).
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    faces_only = vtkPolyData()
    faces_only.DeepCopy(standard)
    companion = voxelbrep.vtkStandardPlaneReversion()
    companion.SetInputData(faces_only)
    companion.Update()
    voxels = companion.GetOutput()
    # One convention for both reversions: the layout of the input (extent, origin, spacing,
    # association of the scalars).
    check.equal(tag + ": companion extent", voxels.GetExtent(), image.GetExtent())
    check.close(tag + ": companion origin", voxels.GetOrigin(), image.GetOrigin())
    check.close(tag + ": companion spacing", voxels.GetSpacing(), image.GetSpacing())
    companion_data = voxels.GetCellData() if cell_data else voxels.GetPointData()
    got = ns.vtk_to_numpy(companion_data.GetArray("Selection")).reshape(values.shape)
    check.true(tag + ": vtkStandardPlaneReversion equals the selection",
               bool((got == binary).all()))
    if labels:
        got_labels = ns.vtk_to_numpy(companion_data.GetArray("Label")).reshape(values.shape)
        check.true(tag + ": labels back", bool((got_labels == values).all()))
    loop_linels = sum(len(c) for c in cells(standard))
    edges = run(f, f.STANDARD_EDGES)
    lines = cells(edges)
    check.equal(tag + ": standard edges cover every loop linel once",
                sum(len(c) - 1 for c in lines), loop_linels // 2)
    if lines:
        check.true(tag + ": an edge separates two faces",
                   bool((cell_array(edges, "FaceId") != cell_array(edges, "OtherFaceId")).all()))
    semi = run(f, f.SEMI_DISCRETE)
    check.equal(tag + ": semi-discrete triangles cover every face",
                len(np.unique(cell_array(semi, "FaceId"))) if faces else 0, faces)
    check.true(tag + ": semi-discrete faces are triangles", all(len(c) == 3 for c in cells(semi)))
    reversion = f.GetOutputDataObject(1)
    attributes = reversion.GetCellData() if cell_data else reversion.GetPointData()
    back = ns.vtk_to_numpy(attributes.GetArray("Selection")).reshape(values.shape)
    check.true(tag + ": reversion equals the selection", bool((back == binary).all()))
    check.equal(tag + ": ReversionMatches", field_value(reversion, "ReversionMatches"), 1)
    return faces


def main():
    rng = np.random.default_rng(3)
    for seed in range(8):
        shape = tuple(rng.integers(2, 13, size=3))
        mask = (rng.random(shape) < rng.uniform(0.1, 0.9)).astype(np.uint8)
        check_case("random %d" % seed, mask)
    mask = (rng.random((9, 7, 8)) < 0.5).astype(np.int16)
    check_case("cell data, shifted", mask, spacing=(0.5, 1.5, 2.0), origin=(-3, 4, 1.25),
               index_min=(2, -5, 7), cell_data=True)
    check_case("mirrored spacing", mask, spacing=(-1.0, 1.0, 1.0), origin=(10, 0, 0))
    labels = rng.integers(0, 4, size=(8, 9, 10)).astype(np.uint8)
    check_case("labels", labels, selected=labels, labels=True)
    # The paper's sphere: integer centres with x^2 + y^2 + z^2 <= 240.
    c = np.arange(-17, 18)
    z, y, x = np.meshgrid(c, c, c, indexing="ij")
    ball = ((x * x + y * y + z * z) <= 240).astype(np.uint8)
    faces = check_case("sphere", ball)
    check.true("sphere: fewer faces than the paper's 135 (got %d)" % faces, faces <= 120)
    # A direction matrix: the faces and the reversion of port 1 work; the companion filter,
    # which has only the faces, refuses (an error, no output) rather than answer wrongly.
    rotated = make_image(mask, direction=[[0, -1, 0], [1, 0, 0], [0, 0, 1]])
    f = voxelbrep.vtkStandardPlanePolyhedrizer()
    f.SetInputData(rotated)
    f.Update()
    back = ns.vtk_to_numpy(f.GetOutputDataObject(1).GetPointData().GetArray("Selection"))
    check.true("rotated: reversion equals the selection",
               bool((back.reshape(mask.shape) == (mask != 0)).all()))
    from vtkmodules.vtkCommonCore import vtkObject
    vtkObject.GlobalWarningDisplayOff()
    companion = voxelbrep.vtkStandardPlaneReversion()
    companion.SetInputConnection(f.GetOutputPort(0))
    companion.Update()
    vtkObject.GlobalWarningDisplayOn()
    check.true("rotated: the companion refuses",
               companion.GetOutput().GetCellData().GetArray("Selection") is None)
    # Empty selection: empty outputs, no error.
    check_case("empty", np.zeros((4, 5, 6), np.uint8))
    check.finish()


main()
