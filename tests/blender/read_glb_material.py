# Blender 3.4, headless: imports a .glb (or an .obj, to compare with Blender's own reading of its
# materials) and prints each material: the image its base colour comes from, its roughness and
# its normal map's strength.
# blender -b --factory-startup --python read_glb_material.py -- FILE.glb|FILE.obj
import sys

import bpy
import numpy

numpy.bool = bool  # Blender 3.4's glTF importer still uses the alias numpy 1.24 removed

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
if path.endswith(".obj"):
    bpy.ops.wm.obj_import(filepath=path)
else:
    bpy.ops.import_scene.gltf(filepath=path)
for material in bpy.data.materials:
    nodes = material.node_tree.nodes
    colour = [n.image for n in nodes if n.type == 'TEX_IMAGE' and n.image and
              any(link.to_socket.name == 'Base Color' for link in n.outputs['Color'].links)]
    if colour:
        image = colour[0]
        texture = f"image {image.size[0]}x{image.size[1]} packed {image.packed_file is not None}"
    else:
        texture = "no image"
    bsdf = next((n for n in nodes if n.type == 'BSDF_PRINCIPLED'), None)
    roughness = f"{bsdf.inputs['Roughness'].default_value:.2f}" if bsdf else "no bsdf"
    normal = [n.inputs['Strength'].default_value for n in nodes if n.type == 'NORMAL_MAP']
    print(f"material {material.name}: {texture}, roughness {roughness}, "
          f"normal map {f'{normal[0]:.2f}' if normal else 'none'}")
