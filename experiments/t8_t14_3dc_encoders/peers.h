/* peers.h - C entry points to the Debian peers' BC5 encoders (adapter in peers.cpp). */
#ifndef T8_T14_PEERS_H
#define T8_T14_PEERS_H

#ifdef __cplusplus
extern "C" {
#endif

/* rgba: width*height*4 bytes, x in R and y in G as UNORM8 of (n + 1) / 2. blocks: 16 bytes per 4x4
 * block, row-major, D3D BC5 layout. Return 0 on success. */
int peer_squish_bc5(const unsigned char *rgba, int width, int height, unsigned char *blocks);
/* quality: 0 fastest, 1 normal, 2 production, 3 highest (nvtt::Quality). */
int peer_nvtt_bc5(const unsigned char *rgba, int width, int height, int quality, unsigned char *blocks);

#ifdef __cplusplus
}
#endif
#endif
