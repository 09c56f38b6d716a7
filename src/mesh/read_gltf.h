#pragma once
// glTF 2.0 input (`.gltf` JSON with external or embedded buffers, `.glb` binary), read once and parsed by radwalk
// itself (the JSON by nlohmann_json).
//
// Geometry: the triangles of every mesh primitive of mode 4 (triangles), 5 (strip) or 6 (fan), indexed or not,
// reached from the default scene's root nodes (`scene`, else scene 0; without scenes, every node that is no
// node's child; without nodes, every mesh once as it is). Each node's global transform (its `matrix`, or
// translation x rotation x scale, times its parents') is applied to the POSITION accessor (FLOAT VEC3); a
// transform with a negative determinant (a mirror) reverses the corner order, so the front stays the front (glTF
// 2.0, "Meshes"). Points and lines (modes 0 to 3) are ignored with a warning. A mesh used by several nodes is
// read once per node.
// Materials: one per glTF material, named as the file names it ("material_K" when it has no name): rho = Kd =
// pbrMetallicRoughness.baseColorFactor's RGB (default 1 1 1, which validate_mesh refuses as rho = 1: give a value
// with --set or scale with --rho-scale); Ke = emissiveFactor x KHR_materials_emissive_strength.emissiveStrength
// (emitted radiance in the scene's unit, default 0); doubleSided true makes the material two-sided
// (Material::two_sided). Textures, metallic and roughness are ignored (a warning names a material with a
// baseColorTexture); a primitive without material gets validate_mesh's default.
// Names: each (node, mesh) pair is a group: object = the node's name ("node_K" if none), group = the mesh's name
// ("mesh_K" if none). Face f is the f-th triangle in reading order (nodes depth first, primitives in order).
// Buffers: a .glb's BIN chunk, `data:` URIs (base64) and files relative to the glTF (read with read_input_file,
// so the run id covers them).
// Bounded: every accessor must lie inside its buffer view and every view inside its buffer before anything is
// read; the JSON nesting is at most 64 deep; the triangles and vertices made (instances counted) are at most
// 1e6 + 8 x the bytes read, so a small file cannot instance a mesh into unbounded memory. Every refusal is one
// InputError naming the file (and the glTF object: "meshes[2].primitives[0]: ...").
#include <functional>
#include <string>
#include <string_view>

#include "mesh/mesh.h"

namespace radwalk {

// Where external buffers come from: read(path) gives the bytes of a file (path resolved against the glTF's
// directory) or throws InputError naming it.
struct GltfResources {
  std::function<std::string(const std::string& path)> read;
};

// Files on disk, each read with read_input_file.
GltfResources gltf_files_on_disk();

// read_gltf_bytes(path, read_input_file(path), gltf_files_on_disk(), options).
Mesh read_gltf(const std::string& path, const ReadOptions& options = {});

// The bytes of a .gltf or .glb (told apart by the GLB magic "glTF" at the start) already read.
Mesh read_gltf_bytes(const std::string& path, std::string_view bytes, const GltfResources& resources,
                     const ReadOptions& options = {});

}  // namespace radwalk
