# Blender 3.4, headless: imports a .glb and prints each material with the image its base colour
# comes from. blender -b --factory-startup --python read_glb_material.py -- FILE.glb
import sys

import bpy
import numpy

numpy.bool = bool  # Blender 3.4's glTF importer still uses the alias numpy 1.24 removed

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
for material in bpy.data.materials:
    images = [n.image for n in material.node_tree.nodes if n.type == 'TEX_IMAGE' and n.image]
    if images:
        image = images[0]
        texture = f"image {image.size[0]}x{image.size[1]} packed {image.packed_file is not None}"
    else:
        texture = "no image"
    print(f"material {material.name}: {texture}")
