// glint's C entry points into the Basis Universal transcoder (vendor/transcoder, v1.16): one KTX2
// image (level 0, layer 0, face 0) of ETC1S (BasisLZ) or UASTC blocks to RGBA8. The Rust side
// (src/lib.rs and glint's scene/ktx2) has checked every count, offset and size against its buffers;
// the transcoder checks the bitstreams themselves and returns false on corrupt data.
#include <cstdint>
#include <mutex>
#include "transcoder/basisu_transcoder.h"

using namespace basist;

static void init_once() {
    static std::once_flag flag;
    std::call_once(flag, [] { basisu_transcoder_init(); });
}

extern "C" {

// ETC1S: the global codebooks (endpoints, selectors, Huffman tables) and one image's colour slice
// (and alpha slice when alpha_len > 0) inside `level`. Writes width * height RGBA8 pixels.
int glint_etc1s_to_rgba(const uint8_t* endpoints, uint32_t endpoints_len, uint32_t num_endpoints,
                        const uint8_t* selectors, uint32_t selectors_len, uint32_t num_selectors,
                        const uint8_t* tables, uint32_t tables_len, const uint8_t* level,
                        uint32_t level_len, uint32_t rgb_offset, uint32_t rgb_len,
                        uint32_t alpha_offset, uint32_t alpha_len, uint32_t width, uint32_t height,
                        uint8_t* out, uint32_t out_pixels) {
    init_once();
    basisu_lowlevel_etc1s_transcoder t;
    if (!t.decode_palettes(num_endpoints, endpoints, endpoints_len, num_selectors, selectors,
                           selectors_len))
        return 1;
    if (!t.decode_tables(tables, tables_len)) return 2;
    const uint32_t bx = (width + 3) / 4, by = (height + 3) / 4;
    if (!t.transcode_image(transcoder_texture_format::cTFRGBA32, out, out_pixels, level, level_len,
                           bx, by, width, height, 0, rgb_offset, rgb_len, alpha_offset, alpha_len,
                           0, alpha_len > 0, false, width, nullptr, height))
        return 3;
    return 0;
}

// UASTC: `blocks` holds the level's 16-byte 4x4 blocks (already inflated from Zstandard).
int glint_uastc_to_rgba(const uint8_t* blocks, uint32_t blocks_len, uint32_t width,
                        uint32_t height, int has_alpha, uint8_t* out, uint32_t out_pixels) {
    init_once();
    basisu_lowlevel_uastc_transcoder t;
    const uint32_t bx = (width + 3) / 4, by = (height + 3) / 4;
    if (!t.transcode_image(transcoder_texture_format::cTFRGBA32, out, out_pixels, blocks,
                           blocks_len, bx, by, width, height, 0, 0, blocks_len, 0, has_alpha != 0,
                           false, width, nullptr, height))
        return 3;
    return 0;
}

}  // extern "C"
