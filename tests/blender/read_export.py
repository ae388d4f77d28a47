# Run by headless Blender (see BlenderReadsExportsTest.cpp):
#   blender -b --factory-startup --python read_export.py -- FORMAT PATH REFERENCE_DIR STEM FPS FRAMES
# Reads a Boneless export the way a user would (OBJ importer, Mesh Cache modifier, glTF importer),
# and compares the vertex positions Blender shows at each of FRAMES (take frames, comma-separated,
# the first of them the first frame exported) with the OBJ frames Boneless wrote into
# REFERENCE_DIR (exact digits). Prints the worst difference as a fraction of the
# bounding-box diagonal and exits 1 if it exceeds float precision.
import sys

import bpy
import numpy

FORMAT, PATH, REFERENCE, STEM, FPS, FRAMES = sys.argv[sys.argv.index("--") + 1:]
FRAMES = [int(f) for f in FRAMES.split(",")]
TOLERANCE = 1e-6  # of the diagonal: float32 storage gives about 1e-7


def reference(frame):
    with open(f"{REFERENCE}/{STEM}_{frame:04d}.obj") as f:
        return numpy.array([[float(x) for x in line.split()[1:4]] for line in f
                            if line.startswith("v ")])


def positions(obj, from_gltf=False):
    mesh = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).to_mesh()
    co = numpy.empty(3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    if from_gltf:  # the importer turns glTF's +Y up into Blender's +Z up: (x, y, z) -> (x, -z, y)
        co = numpy.stack([co[:, 0], co[:, 2], -co[:, 1]], axis=1)
    return co


def import_obj(path):
    # Blender's default axes turn the file; these keep it as written.
    bpy.ops.wm.obj_import(filepath=path, forward_axis='Y', up_axis='Z')
    return bpy.context.selected_objects[0]


def compare(frame, got):
    want = reference(frame)
    if got.shape != want.shape:
        sys.exit(f"{FORMAT} frame {frame}: Blender shows {got.shape[0]} vertices, "
                 f"Boneless wrote {want.shape[0]}")
    diagonal = numpy.linalg.norm(want.max(axis=0) - want.min(axis=0))
    return numpy.abs(got - want).max() / diagonal


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
worst = 0.0
if FORMAT == "obj":
    for frame in FRAMES:
        obj = import_obj(f"{PATH}/{STEM}_{frame:04d}.obj")
        worst = max(worst, compare(frame, positions(obj)))
        bpy.data.objects.remove(obj)
elif FORMAT in ("pc2", "mdd"):
    # The cache deforms the first frame's mesh. In its default Frame mode the modifier plays cache
    # sample n at scene frame frame_start + n (a PC2's own start frame is only read in Time mode).
    obj = import_obj(f"{REFERENCE}/{STEM}_{FRAMES[0]:04d}.obj")
    cache = obj.modifiers.new("cache", 'MESH_CACHE')
    cache.cache_format = FORMAT.upper()
    cache.filepath = PATH
    cache.frame_start = FRAMES[0]  # the first frame exported
    for frame in FRAMES:
        scene.frame_set(frame)
        worst = max(worst, compare(frame, positions(obj)))
elif FORMAT == "glb":
    numpy.bool = bool  # Blender 3.4's importer still uses it; numpy 1.24 removed it
    scene.render.fps = int(FPS)  # keys land on whole frames: take frame n at scene frame n
    bpy.ops.import_scene.gltf(filepath=PATH)
    obj = next(o for o in bpy.context.selected_objects if o.type == 'MESH')
    for frame in FRAMES:
        scene.frame_set(frame)
        worst = max(worst, compare(frame, positions(obj, from_gltf=True)))
    # Where a user sees it: the node stands the body up (Blender's +Z) at its size in metres.
    co = positions(obj)
    world = co @ numpy.array(obj.matrix_world)[:3, :3].T
    extent = world.max(axis=0) - world.min(axis=0)
    print(f"glb: stands {extent[2]:.2f} m tall, {extent[0]:.2f} by {extent[1]:.2f} m across")
    if extent[2] < extent.max() or not 1.0 < extent[2] < 2.5:
        sys.exit("glb: the body does not stand upright at a human's height")
else:
    sys.exit(f"unknown format {FORMAT}")

print(f"{FORMAT}: frames {FRAMES} read back within {worst:.2e} of the diagonal")
sys.exit(0 if worst <= TOLERANCE else 1)
