# Blender 3.4, headless: imports one OBJ frame and prints what an artist's file keeps through it.
# blender -b --factory-startup --python read_obj_faces.py -- FRAME.obj
import sys

import bpy

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.obj_import(filepath=path)
mesh = bpy.context.selected_objects[0].data
quads = sum(1 for p in mesh.polygons if len(p.vertices) == 4)
print(f"faces: {len(mesh.vertices)} vertices, {len(mesh.polygons)} polygons, {quads} quads, "
      f"{len(mesh.uv_layers)} uv layers")
