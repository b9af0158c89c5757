"""vtkEVMBoundaryFilter on 2D images: the contour hierarchy against OpenCV and scipy.

Usage: TestEVMBoundary2D.py random
       TestEVMBoundary2D.py images DATA_DIR   (exits 77, "skipped", when DATA_DIR is absent)

With MergeNonManifoldFaces ON the filter's faces are 8-connected, which is OpenCV's
foreground connectivity, so its loops must match cv2.findContours(RETR_TREE) on the image
padded with a one-pixel zero border: as many outer loops as outer contours, as many hole
loops as hole contours, the same depth histogram, the same number of holes per face and of
faces inside the holes of each face. Independently of OpenCV:

* the signed (shoelace) areas of the loops add up to the foreground area; outer loops are
  counter-clockwise, holes clockwise; the area of each face (its outer loop minus its
  holes) is the pixel count of one 8-connected component (scipy.ndimage.label);
* with MergeNonManifoldFaces OFF the faces are the 4-connected components;
* NumberOfVoxels and NumberOfExtremeVertices equal the numpy counts (pixels with an odd
  number of the 4 incident pixels set) and, for the real images, the MANIFEST numbers.
"""

import os
import sys
from collections import Counter

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import voxelbrep_testing as vt  # noqa: E402

import voxelbrep  # noqa: E402

try:
    import cv2
except ImportError:  # python3-opencv is a test dependency (scripts/install-deps.sh)
    cv2 = None

check = vt.Checker("TestEVMBoundary2D")


def run_filter(image, merge, mode="Loops"):
    f = voxelbrep.vtkEVMBoundaryFilter()
    f.SetInputData(image)
    f.SetMergeNonManifoldFaces(merge)
    if mode == "Loops":
        f.SetOutputModeToLoops()
    else:
        f.SetOutputModeToPolylines()
    f.Update()
    return f.GetOutput()


def loops_of(output, plane_axes):
    """Per loop: signed area in the image plane, LoopType, FaceId, ParentFace, Depth."""
    pts = vt.points(output)
    areas = np.array([vt.signed_area_2d(pts[vt.open_loop(ids)], *plane_axes)
                      for ids in vt.cells(output)])
    return {
        "area": areas,
        "type": vt.cell_array(output, "LoopType"),
        "face": vt.cell_array(output, "FaceId"),
        "parent": vt.cell_array(output, "ParentFace"),
        "depth": vt.cell_array(output, "Depth"),
    }


def opencv_tree(mask):
    """Depth of every contour and, per outer contour, its holes and the outer contours
    directly inside those holes (OpenCV: 8-connected foreground, 4-connected holes)."""
    img = np.pad(mask.astype(np.uint8) * 255, 1)
    found = cv2.findContours(img, cv2.RETR_TREE, cv2.CHAIN_APPROX_SIMPLE)
    hierarchy = found[-1]
    if hierarchy is None:
        return np.zeros(0, int), [], []
    h = hierarchy[0]
    n = len(h)
    depth = np.zeros(n, int)
    for i in range(n):
        p = h[i][3]
        while p >= 0:
            depth[i] += 1
            p = h[p][3]
    children = [[] for _ in range(n)]
    for i in range(n):
        if h[i][3] >= 0:
            children[h[i][3]].append(i)
    holes_per_face = sorted(len(children[i]) for i in range(n) if depth[i] % 2 == 0)
    inner_per_face = sorted(sum(len(children[c]) for c in children[i])
                            for i in range(n) if depth[i] % 2 == 0)
    return depth, holes_per_face, inner_per_face


def component_sizes(mask, eight):
    from scipy import ndimage

    s = ndimage.generate_binary_structure(2, 2 if eight else 1)
    labels, n = ndimage.label(mask, structure=s)
    return sorted(np.bincount(labels.ravel())[1:].tolist()) if n else []


def check_image(name, mask, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0),
                index_min=(0, 0, 0), cell_data=False, expected_manifest=None,
                flat_axis=2, use_opencv=True):
    """mask: 2D [rows, columns] foreground. The image lies in the plane normal to
    flat_axis (columns run along the first remaining axis, rows along the second)."""
    mask = mask.astype(bool)
    pixel_area = float(np.prod([s for d, s in enumerate(spacing) if d != flat_axis]))
    if flat_axis == 2:
        values = mask[np.newaxis, :, :]
    elif flat_axis == 1:
        values = mask[:, np.newaxis, :]
    else:
        values = mask[:, :, np.newaxis]
    plane_axes = [d for d in range(3) if d != flat_axis]
    image = vt.make_image(values.astype(np.uint8), spacing, origin, index_min, cell_data)
    fg = int(mask.sum())
    ev = vt.extreme_vertices(mask)
    if expected_manifest:
        check.equal(name + " MANIFEST foreground (numpy)", fg, expected_manifest["fg"])
        if "ev" in expected_manifest:
            check.equal(name + " MANIFEST EV (numpy)", ev, expected_manifest["ev"])

    for merge in (True, False):
        tag = "%s [merge %s]" % (name, merge)
        out = run_filter(image, merge)
        check.equal(tag + " NumberOfVoxels", vt.field_value(out, "NumberOfVoxels"), fg)
        check.equal(tag + " NumberOfExtremeVertices",
                    vt.field_value(out, "NumberOfExtremeVertices"), ev)
        if expected_manifest:
            check.equal(tag + " NumberOfVoxels = MANIFEST",
                        vt.field_value(out, "NumberOfVoxels"), expected_manifest["fg"])
            if "ev" in expected_manifest:
                check.equal(tag + " NumberOfExtremeVertices = MANIFEST",
                            vt.field_value(out, "NumberOfExtremeVertices"),
                            expected_manifest["ev"])
        if fg == 0:
            check.equal(tag + " no cells", out.GetNumberOfCells(), 0)
            continue
        check.equal(tag + " polygons only", out.GetNumberOfPolys(), out.GetNumberOfCells())
        loops = loops_of(out, plane_axes)
        outer = loops["type"] == 0
        hole = loops["type"] == 1
        faces, holes = vt.components_and_holes_2d(mask, merge)
        check.equal(tag + " outer loops = components", int(outer.sum()), faces)
        check.equal(tag + " hole loops = holes", int(hole.sum()), holes)
        check.equal(tag + " NumberOfFaces", vt.field_value(out, "NumberOfFaces"), faces)
        check.equal(tag + " NumberOfHoles", vt.field_value(out, "NumberOfHoles"), holes)
        if expected_manifest and merge and "cc8" in expected_manifest:
            check.equal(tag + " NumberOfFaces = MANIFEST cc8",
                        vt.field_value(out, "NumberOfFaces"), expected_manifest["cc8"])
        if expected_manifest and not merge and "cc4" in expected_manifest:
            check.equal(tag + " NumberOfFaces = MANIFEST cc4",
                        vt.field_value(out, "NumberOfFaces"), expected_manifest["cc4"])

        # Areas: loops signed by orientation, faces = components.
        # In the x-y plane outer loops run counter-clockwise seen from +z. For images normal
        # to x or y only consistency is required (the shoelace runs in the plane's axes in
        # increasing order, whose handedness is a matter of convention).
        sign = 1.0 if flat_axis == 2 else float(np.sign(loops["area"].sum()))
        area = loops["area"] * sign
        check.close(tag + " sum of signed loop areas", float(area.sum()), fg * pixel_area)
        check.true(tag + " outer loops counter-clockwise", bool(np.all(area[outer] > 0)))
        check.true(tag + " hole loops clockwise", bool(np.all(area[hole] < 0)))
        face_area = Counter()
        for a, f in zip(area, loops["face"]):
            face_area[int(f)] += a
        check.close(tag + " face areas = component sizes",
                    np.array(sorted(face_area.values())) / pixel_area,
                    np.array(component_sizes(mask, merge), float))

        # Hierarchy: a hole's parent is its face, one level deeper; a face inside a hole
        # is two levels below the face owning the hole.
        depth_of_face = {int(f): int(d) for f, d, t in
                         zip(loops["face"], loops["depth"], loops["type"]) if t == 0}
        check.true(tag + " hole ParentFace/Depth", all(
            p == f and d == depth_of_face[int(f)] + 1
            for f, p, d in zip(loops["face"][hole], loops["parent"][hole],
                               loops["depth"][hole])))
        check.true(tag + " face ParentFace/Depth", all(
            (p == -1 and d == 0) or (p >= 0 and d == depth_of_face.get(int(p), -9) + 2)
            for p, d in zip(loops["parent"][outer], loops["depth"][outer])))
        check.true(tag + " depth parity", bool(np.all(loops["depth"] % 2 == loops["type"])))

        # The same loops as polylines.
        lines = run_filter(image, merge, "Polylines")
        check.equal(tag + " polylines = polygons", lines.GetNumberOfLines(),
                    out.GetNumberOfCells())
        line_loops = loops_of(lines, plane_axes)
        check.close(tag + " polyline areas", np.sort(line_loops["area"]),
                    np.sort(loops["area"]))

        if merge and use_opencv and cv2 is not None:
            depth, cv_holes_per_face, cv_inner_per_face = opencv_tree(mask)
            check.equal(tag + " outer loops = OpenCV outer contours", int(outer.sum()),
                        int(np.count_nonzero(depth % 2 == 0)))
            check.equal(tag + " hole loops = OpenCV hole contours", int(hole.sum()),
                        int(np.count_nonzero(depth % 2 == 1)))
            check.equal(tag + " depth histogram = OpenCV",
                        np.bincount(loops["depth"]).tolist(), np.bincount(depth).tolist())
            holes_per_face = Counter(int(f) for f in loops["face"][hole])
            check.equal(tag + " holes per face = OpenCV",
                        sorted(holes_per_face.get(f, 0) for f in depth_of_face),
                        cv_holes_per_face)
            inner = Counter(int(p) for p in loops["parent"][outer] if p >= 0)
            check.equal(tag + " faces inside the holes of each face = OpenCV",
                        sorted(inner.get(f, 0) for f in depth_of_face), cv_inner_per_face)


def random_images():
    rng = np.random.default_rng(7)
    # Hand-made cases: a pinched ring (a face touching itself at a vertex), nested rings,
    # a checkerboard, a full image.
    ring = np.zeros((6, 6), bool)
    ring[1:5, 1:5] = True
    ring[2:4, 2:4] = False
    pinched = ring.copy()
    pinched[1, 1] = False
    pinched[2, 2] = True
    pinched[2, 3] = False
    nested = np.zeros((11, 11), bool)
    nested[1:10, 1:10] = True
    nested[2:9, 2:9] = False
    nested[3:8, 3:8] = True
    nested[4:7, 4:7] = False
    nested[5, 5] = True
    checker = (np.indices((7, 8)).sum(axis=0) % 2).astype(bool)
    for name, m in (("ring", ring), ("pinched ring", pinched), ("nested", nested),
                    ("checkerboard", checker), ("full", np.ones((4, 5), bool)),
                    ("empty", np.zeros((4, 5), bool))):
        check_image(name, m, spacing=(0.5, 2.0, 3.0), origin=(1.0, -2.0, 0.5),
                    index_min=(3, -1, 4))
    for i in range(300):
        h, w = rng.integers(2, 17, size=2)
        m = rng.random((h, w)) < rng.uniform(0.2, 0.8)
        spacing = tuple(rng.uniform(0.25, 3.0, size=3))
        origin = tuple(rng.uniform(-10, 10, size=3))
        index_min = tuple(int(v) for v in rng.integers(-5, 5, size=3))
        check_image("random %d (%dx%d)" % (i, w, h), m, spacing, origin, index_min,
                    cell_data=bool(i % 3 == 1), flat_axis=2 if i % 5 else int(i // 5 % 2))
    # Lines of one word of 64 pixels, one less and one more, two words: the sweep's words of
    # pixels and of corners end there.
    for i, (h, w) in enumerate(((2, 129), (129, 2), (63, 65), (64, 64), (65, 63), (128, 129))):
        m = rng.random((h, w)) < 0.5
        check_image("word sizes %d (%dx%d)" % (i, w, h), m, (1.0, 1.0, 1.0), (0.0, 0.0, 0.0),
                    (-3, 2, 0), cell_data=bool(i % 2), flat_axis=2)
    # Over 250,000 extreme vertices (about 277,000): the corners numbered by column before the
    # sweep (vbr::FewestVerticesByColumn), smaller images take the sort.
    check_image("corners by column (760x760)", rng.random((760, 760)) < 0.5, (0.5, 2.0, 1.0),
                (1.0, -2.0, 0.0), (2, -1, 0), flat_axis=2)


def real_images(data_dir):
    folder = os.path.join(data_dir, "2d", "skimage")
    if not os.path.isdir(folder):
        print("SKIPPED: %s is absent (set VOXELBREP_DATA_DIR)" % folder)
        sys.exit(vt.SKIP_RETURN_CODE)
    if cv2 is None:
        print("SKIPPED: python3-opencv (cv2) is not installed")
        sys.exit(vt.SKIP_RETURN_CODE)

    def grey(name):
        return cv2.imread(os.path.join(folder, name), cv2.IMREAD_UNCHANGED)

    horse = grey("horse.png").astype(float)  # RGBA (OpenCV: BGRA)
    luminance = 0.2125 * horse[..., 2] + 0.7154 * horse[..., 1] + 0.0721 * horse[..., 0]
    cases = [
        ("horse", luminance < 128, {"fg": 43412, "ev": 1180, "cc8": 1}),
        ("page", grey("page.png") <= 157, {"fg": 26526, "ev": 5848, "cc4": 289, "cc8": 230}),
        ("text", grey("text.png") <= 109, None),
        ("coins", grey("coins.png") > 107, {"fg": 45117, "ev": 5938, "cc4": 154, "cc8": 96}),
    ]
    for name, mask, manifest in cases:
        check_image(name, mask, expected_manifest=manifest)
        print("%s: %d foreground pixels checked" % (name, int(mask.sum())))


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == "images":
        real_images(sys.argv[2] if len(sys.argv) > 2 else os.environ.get("VOXELBREP_DATA_DIR",
                                                                          ""))
    else:
        if cv2 is None:
            print("note: cv2 missing, the OpenCV comparison is skipped")
        random_images()
    check.finish()


if __name__ == "__main__":
    main()
