// peers.cpp - extern "C" adapter over libsquish (kBc5) and NVIDIA Texture Tools 2.0 (Format_BC5),
// whose APIs are C++ only (libnvtt exports no C entry points: `nm -D libnvtt.so` shows only nv::/nvtt::
// symbols). Both take 8-bit input, so they see the normal map quantised to 8 bits per channel.
#include "peers.h"

#include <cstring>
#include <squish.h>
#include <nvtt/nvtt.h>
#include <vector>

int peer_squish_bc5(const unsigned char *rgba, int width, int height, unsigned char *blocks)
{
    squish::CompressImage(rgba, width, height, blocks, squish::kBc5);
    return 0;
}

namespace {
// Collects the compressed bytes of the single mip level nvtt writes (no DDS header requested).
struct Collector : nvtt::OutputHandler {
    std::vector<unsigned char> bytes;
    void beginImage(int, int, int, int, int, int) override {}
    bool writeData(const void *data, int size) override
    {
        const unsigned char *p = static_cast<const unsigned char *>(data);
        bytes.insert(bytes.end(), p, p + size);
        return true;
    }
};
} // namespace

int peer_nvtt_bc5(const unsigned char *rgba, int width, int height, int quality, unsigned char *blocks)
{
    std::vector<unsigned char> bgra((size_t)width * height * 4);
    for (size_t i = 0; i < (size_t)width * height; ++i) { // nvtt's input is BGRA
        bgra[4 * i + 0] = rgba[4 * i + 2];
        bgra[4 * i + 1] = rgba[4 * i + 1];
        bgra[4 * i + 2] = rgba[4 * i + 0];
        bgra[4 * i + 3] = rgba[4 * i + 3];
    }
    nvtt::InputOptions in;
    in.setTextureLayout(nvtt::TextureType_2D, width, height);
    in.setFormat(nvtt::InputFormat_BGRA_8UB);
    in.setMipmapData(bgra.data(), width, height);
    in.setMipmapGeneration(false);
    in.setGamma(1.0f, 1.0f); // no gamma conversion of the normal components
    nvtt::CompressionOptions co;
    co.setFormat(nvtt::Format_BC5);
    co.setQuality((nvtt::Quality)quality);
    Collector out;
    nvtt::OutputOptions oo;
    oo.setOutputHandler(&out);
    oo.setOutputHeader(false);
    nvtt::Compressor compressor;
    compressor.enableCudaAcceleration(false);
    if (!compressor.process(in, co, oo))
        return 1;
    const size_t need = (size_t)(width / 4) * (height / 4) * 16;
    if (out.bytes.size() < need)
        return 2;
    std::memcpy(blocks, out.bytes.data(), need);
    return 0;
}
