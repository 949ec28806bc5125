// glint's C entry points into the vendored Draco decoder (vendor/, v1.5.7): one Draco mesh stream
// decoded into an opaque handle, then its counts, indices and attributes (by Draco unique id)
// copied into buffers the caller allocated. Every entry point catches all C++ exceptions (a failed
// allocation is std::bad_alloc) so none crosses into Rust; errors are codes plus a message.
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "draco/compression/decode.h"
#include "draco/core/decoder_buffer.h"
#include "draco/mesh/mesh.h"

namespace {

struct Handle {
  std::unique_ptr<draco::Mesh> mesh;
};

void set_message(char* err, size_t err_len, const std::string& msg) {
  if (err == nullptr || err_len == 0) return;
  const size_t n = msg.size() < err_len - 1 ? msg.size() : err_len - 1;
  std::memcpy(err, msg.data(), n);
  err[n] = 0;
}

// Copies every point's value of `attr`, converted by Draco to T with `components` components.
template <typename T>
int copy_values(const draco::PointAttribute* attr, int components, uint32_t points, void* out) {
  T* dst = static_cast<T*>(out);
  for (uint32_t p = 0; p < points; ++p) {
    const draco::AttributeValueIndex v = attr->mapped_index(draco::PointIndex(p));
    if (v.value() >= attr->size()) return 4;
    if (!attr->ConvertValue<T>(v, static_cast<int8_t>(components), dst + size_t(p) * components))
      return 5;
  }
  return 0;
}

}  // namespace

extern "C" {

// Decodes `len` bytes of a Draco mesh. Refuses (code 1, message in `err`) a stream that is corrupt,
// is not a triangle mesh, or declares more than `max_faces` faces or `max_points` vertices (checked
// inside the decoder before it allocates). On success `*out` owns the mesh: free it with
// glint_draco_free.
int glint_draco_decode(const uint8_t* data, size_t len, uint32_t max_faces, uint32_t max_points,
                       void** out, char* err, size_t err_len) {
  *out = nullptr;
  try {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), len);
    auto kind = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!kind.ok()) {
      set_message(err, err_len, kind.status().error_msg_string());
      return 1;
    }
    if (kind.value() != draco::TRIANGULAR_MESH) {
      set_message(err, err_len, "not a triangle mesh (a point cloud?)");
      return 1;
    }
    draco::Decoder decoder;
    const int int_max = 0x7fffffff;
    draco::DecoderOptions* opts = decoder.options();
    opts->SetGlobalInt("glint_max_faces", max_faces > uint32_t(int_max) ? int_max : int(max_faces));
    opts->SetGlobalInt("glint_max_points",
                       max_points > uint32_t(int_max) ? int_max : int(max_points));
    auto mesh = decoder.DecodeMeshFromBuffer(&buffer);
    if (!mesh.ok()) {
      set_message(err, err_len, mesh.status().error_msg_string());
      return 1;
    }
    std::unique_ptr<Handle> h(new Handle);
    h->mesh = std::move(mesh).value();
    if (h->mesh == nullptr) {
      set_message(err, err_len, "decoder returned no mesh");
      return 1;
    }
    *out = h.release();
    return 0;
  } catch (const std::bad_alloc&) {
    set_message(err, err_len, "out of memory");
    return 2;
  } catch (const std::exception& e) {
    set_message(err, err_len, e.what());
    return 3;
  } catch (...) {
    set_message(err, err_len, "unknown C++ exception");
    return 3;
  }
}

void glint_draco_free(void* handle) { delete static_cast<Handle*>(handle); }

// The decoded mesh's face and point (vertex) counts.
void glint_draco_counts(const void* handle, uint32_t* faces, uint32_t* points) {
  const draco::Mesh& m = *static_cast<const Handle*>(handle)->mesh;
  *faces = m.num_faces();
  *points = m.num_points();
}

// Writes the 3 * faces point indices into `out` (which holds `out_len` of them). 0 on success,
// 6 when `out_len` does not match, 4 when an index is not below the point count.
int glint_draco_indices(const void* handle, uint32_t* out, size_t out_len) {
  const draco::Mesh& m = *static_cast<const Handle*>(handle)->mesh;
  if (out_len != size_t(m.num_faces()) * 3) return 6;
  const uint32_t points = m.num_points();
  for (uint32_t f = 0; f < m.num_faces(); ++f) {
    const draco::Mesh::Face& face = m.face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = face[k].value();
      if (i >= points) return 4;
      out[size_t(f) * 3 + k] = i;
    }
  }
  return 0;
}

// The number of components of the attribute with Draco unique id `id`, or 0 when there is none.
int glint_draco_attribute_components(const void* handle, uint32_t id) {
  const draco::Mesh& m = *static_cast<const Handle*>(handle)->mesh;
  const draco::PointAttribute* a = m.GetAttributeByUniqueId(id);
  return a == nullptr ? 0 : a->num_components();
}

// Writes every point's value of attribute `id` as `components` values of glTF component type
// `component_type` (5120 i8, 5121 u8, 5122 i16, 5123 u16, 5125 u32, 5126 f32) into `out`, which
// holds `out_bytes` bytes. 0 on success; 7 no such attribute, 8 unknown component type, 6 size
// mismatch, 4 bad value index, 5 a value that does not convert (out of range, NaN), 2 out of memory.
int glint_draco_attribute(const void* handle, uint32_t id, int component_type, int components,
                          void* out, size_t out_bytes) {
  try {
    const draco::Mesh& m = *static_cast<const Handle*>(handle)->mesh;
    const draco::PointAttribute* a = m.GetAttributeByUniqueId(id);
    if (a == nullptr) return 7;
    size_t size = 0;
    switch (component_type) {
      case 5120: case 5121: size = 1; break;
      case 5122: case 5123: size = 2; break;
      case 5125: case 5126: size = 4; break;
      default: return 8;
    }
    if (components < 1 || components > 16) return 6;
    if (out_bytes != size_t(m.num_points()) * size_t(components) * size) return 6;
    const uint32_t n = m.num_points();
    switch (component_type) {
      case 5120: return copy_values<int8_t>(a, components, n, out);
      case 5121: return copy_values<uint8_t>(a, components, n, out);
      case 5122: return copy_values<int16_t>(a, components, n, out);
      case 5123: return copy_values<uint16_t>(a, components, n, out);
      case 5125: return copy_values<uint32_t>(a, components, n, out);
      default: return copy_values<float>(a, components, n, out);
    }
  } catch (...) {
    return 2;
  }
}

}  // extern "C"
