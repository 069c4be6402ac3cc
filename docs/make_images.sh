#!/usr/bin/env bash
# Regenerates the pictures in docs/images with tessera itself. Needs a build (scripts/setup.sh),
# ffmpeg (to put the AOVs side by side), the Stanford bunny from Debian's glmark2-data, Debian's
# assimp-testmodels and blender-data (an environment image).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
tessera="$root/build/apps/tessera/tessera"
out="$root/docs/images"
bunny=/usr/share/glmark2/models/bunny.obj
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

"$tessera" cube -w 240 -h 240 -fps 15 -dur 3s -axes -out "$out/cube.gif"

common=(--resolution 320,320)
"$tessera" render "$bunny" "${common[@]}" -o "$tmp/color.png"
"$tessera" render "$bunny" "${common[@]}" --aov id -o "$tmp/id.png"
"$tessera" render "$bunny" "${common[@]}" --aov normal -o "$tmp/normal.png"
ffmpeg -loglevel error -y -i "$tmp/color.png" -i "$tmp/id.png" -i "$tmp/normal.png" \
  -filter_complex hstack=inputs=3 "$out/aovs.png"
# Anti-aliasing: the same close-up of the ear and the Y axis at 1x, 4x MSAA and 4x MSAA with 16
# jittered frames, each pixel shown 3x3.
closeup=(--resolution 160,120 --camera-position -0.1,1.0,2.6 --camera-focal-point -0.2,0.6,0
  --camera-view-angle 28 --axes)
"$tessera" render "$bunny" "${closeup[@]}" --msaa 1 -o "$tmp/aa1.png"
"$tessera" render "$bunny" "${closeup[@]}" --msaa 4 -o "$tmp/aa4.png"
"$tessera" render "$bunny" "${closeup[@]}" --msaa 4 --samples 16 -o "$tmp/aa16.png"
ffmpeg -loglevel error -y -i "$tmp/aa1.png" -i "$tmp/aa4.png" -i "$tmp/aa16.png" -filter_complex \
  "[0]scale=iw*3:ih*3:flags=neighbor[a];[1]scale=iw*3:ih*3:flags=neighbor[b];[2]scale=iw*3:ih*3:flags=neighbor[c];[a][b][c]hstack=inputs=3" \
  "$out/antialiasing.png"
# Projections: the same room (docs/projection_room.py) as a 360x180 panorama and a 180-degree
# fisheye, from one camera.
python3 "$root/docs/projection_room.py" "$tmp/room" "$bunny"
room=(--camera-position 0.5,1.7,1.5 --camera-focal-point 0,1.2,-2 --background-color 0.45,0.62,0.85)
"$tessera" render "$tmp/room/room.obj" "${room[@]}" --projection spherical --resolution 1024,512 \
  -o "$tmp/panorama.png"
"$tessera" render "$tmp/room/room.obj" "${room[@]}" --projection fisheye --resolution 512,512 \
  -o "$tmp/fisheye.png"
ffmpeg -loglevel error -y -i "$tmp/panorama.png" -i "$tmp/fisheye.png" \
  -filter_complex hstack=inputs=2 "$out/projections.png"
# Diagnostics: the bunny's overdraw (depth tests per pixel) as a heatmap with its legend.
"$tessera" render "$bunny" --resolution 480,360 --aov overdraw-heatmap -o "$out/overdraw_heatmap.png"
# Lights: the bunny lit by a warm point light and a blue spot light (docs/rendering.md, Lights).
"$tessera" render "$bunny" --resolution 480,360 --camera-position 0.6,0.8,4.2 \
  --camera-focal-point 0,0,0 --light point:-1.6,1.2,1.6:1,0.7,0.45:4 \
  --light spot:1.8,2.2,1.6:-1.3,-2.5,-1.4:8,14:0.45,0.65,1:8 --ambient 0.02,0.02,0.02 \
  -o "$out/lights.png"
# PBR: Debian assimp-data's ClearCoat test (the base layer), smooth (Lambert) against pbr, and
# pbr lit by Blender's studio environment (Debian's blender-data), shown behind it.
clearcoat=/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf
studio=/usr/share/blender/datafiles/studiolights/world/studio.exr
"$tessera" render "$clearcoat" --resolution 480,480 --shading smooth -o "$tmp/smooth.png"
"$tessera" render "$clearcoat" --resolution 480,480 -o "$tmp/pbr.png"
"$tessera" render "$clearcoat" --resolution 480,480 --hdri "$studio" --hdri-background \
  -o "$tmp/pbr_hdri.png"
ffmpeg -loglevel error -y -i "$tmp/smooth.png" -i "$tmp/pbr.png" -i "$tmp/pbr_hdri.png" \
  -filter_complex hstack=inputs=3 "$out/pbr.png"
# Shadows: the projection room under a low sun, without and with --shadows.
sun=(--camera-position 2.2,2.6,2.8 --camera-focal-point -0.3,0.6,-1.5
  --background-color 0.45,0.62,0.85 --resolution 480,360
  --light directional:0.5,-1,-0.35:1,0.95,0.85:0.9 --ambient 0.15,0.15,0.17)
"$tessera" render "$tmp/room/room.obj" "${sun[@]}" -o "$tmp/sun.png"
"$tessera" render "$tmp/room/room.obj" "${sun[@]}" --shadows -o "$tmp/sun_shadows.png"
ffmpeg -loglevel error -y -i "$tmp/sun.png" -i "$tmp/sun_shadows.png" \
  -filter_complex hstack=inputs=2 "$out/shadows.png"
# Materials and light on one model: the room's bunny made gold metal (Pm 1, Pr 0.3) and its plinth
# rough, under a low sun: smooth (Lambert), pbr, pbr + --shadows, pbr + --shadows + --hdri (a sky
# written by docs/sky_hdr.py).
sed -e 's/^Kd 0.95 0.95 0.95$/Kd 1.0 0.78 0.34\nPm 1\nPr 0.3/' \
  -e 's/^Kd 0.55 0.5 0.6$/Kd 0.55 0.5 0.6\nPr 0.6/' "$tmp/room/room.mtl" >"$tmp/gold.mtl"
mv "$tmp/gold.mtl" "$tmp/room/room.mtl"
python3 "$root/docs/sky_hdr.py" "$tmp/sky.hdr" 256
gold=(--camera-position 2.2,2.6,2.8 --camera-focal-point -0.3,0.6,-1.5
  --background-color 0.45,0.62,0.85 --resolution 400,300
  --light directional:0.5,-1,-0.35:1,0.95,0.85:2.5 --ambient 0.15,0.15,0.17)
"$tessera" render "$tmp/room/room.obj" "${gold[@]}" --shading smooth -o "$tmp/m_smooth.png"
"$tessera" render "$tmp/room/room.obj" "${gold[@]}" --shading pbr -o "$tmp/m_pbr.png"
"$tessera" render "$tmp/room/room.obj" "${gold[@]}" --shading pbr --shadows -o "$tmp/m_shadows.png"
"$tessera" render "$tmp/room/room.obj" "${gold[@]}" --shading pbr --shadows --hdri "$tmp/sky.hdr" \
  -o "$tmp/m_hdri.png"
ffmpeg -loglevel error -y -i "$tmp/m_smooth.png" -i "$tmp/m_pbr.png" -i "$tmp/m_shadows.png" \
  -i "$tmp/m_hdri.png" -filter_complex "[0][1]hstack[t];[2][3]hstack[b];[t][b]vstack" \
  "$out/materials.png"
# The painter's algorithm against the z-buffer (a sphere pierced by a blade), and --edges on a
# quad-faced sphere and a cube (docs/painter_scene.py writes both scenes).
python3 "$root/docs/painter_scene.py" "$tmp/painter"
painter=(--resolution 240,180 --camera-position 0,1.5,6 --camera-focal-point 0,0,0
  --background-color 0.9,0.9,0.9)
"$tessera" render "$tmp/painter/blade.obj" "${painter[@]}" -o "$tmp/zbuffer.png"
"$tessera" render "$tmp/painter/blade.obj" "${painter[@]}" --visibility painter -o "$tmp/painter.png"
ffmpeg -loglevel error -y -i "$tmp/zbuffer.png" -i "$tmp/painter.png" \
  -filter_complex hstack=inputs=2 "$out/painter.png"
"$tessera" render "$tmp/painter/shapes.obj" --resolution 360,200 --camera-position 0.5,2,6.5 \
  --camera-focal-point 0,0,0 --shading flat --background-color 0.9,0.9,0.9 --edges \
  --edge-color 0.1,0.1,0.1 \
  -o "$out/edges.png"

# A glTF animation (docs/rendering.md, "Animations"): docs/animated_scene.py's hub and moon.
python3 "$(dirname "$0")/animated_scene.py" "$tmp/orbit"
"$tessera" render "$tmp/orbit/orbit.gltf" --animation-index 0 --fps 12 --resolution 240x160 \
  --shading flat -o "$out/animation.gif"
# A ground grid under a model (--grid; glmark2-data's horse, read through assimp).
"$tessera" render /usr/share/glmark2/models/horse.3ds --grid --resolution 480,300 -o "$out/grid.png"
# A PLY point cloud (20,000 points on a sphere, scripts/point_cloud_ply.py) as discs and as sprites.
python3 "$root/scripts/point_cloud_ply.py" "$tmp/sphere.ply" 20000
"$tessera" render "$tmp/sphere.ply" --resolution 300,220 --point-size 3 -o "$tmp/discs.png"
"$tessera" render "$tmp/sphere.ply" --resolution 300,220 --point-size 5 --point-sprites \
  -o "$tmp/sprites.png"
ffmpeg -loglevel error -y -i "$tmp/discs.png" -i "$tmp/sprites.png" -filter_complex hstack=inputs=2 \
  "$out/points_ply.png"
