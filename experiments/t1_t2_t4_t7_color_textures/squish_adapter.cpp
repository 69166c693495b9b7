// squish_adapter.cpp - C entry point to libsquish's BC1 encoder for the side-by-side (T1, T2).
#include <squish.h>

#include "textures_exp.h"

extern "C" void squish_bc1_encode(const unsigned char *rgba, int width, int height, void *blocks, int effort)
{
    int fit = effort <= 0 ? squish::kColourRangeFit
                          : (effort == 1 ? squish::kColourClusterFit : squish::kColourIterativeClusterFit);
    // NULL metric: uniform RGB weights, the error sol's encoder minimises too.
    squish::CompressImage(rgba, width, height, blocks, squish::kDxt1 | fit, nullptr);
}
