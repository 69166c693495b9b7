/* degenerate_survey.c - issue 13's constructed hard blocks (see degenerate_survey.h). */
#include "degenerate_survey.h"

#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

const double survey_spreads[SURVEY_SPREADS] = {0.0, 0.01, 0.03, 0.1, 0.3, 1.0, 2.0};

static const char *const family_names[SURVEY_FAMILIES] = {
    "away-arc", "rim-arc", "half-away-arc", "rim-jitter", "away-cone", "azimuth", "away-cone2",
    "below-rim", "flat", "equal", "down", "equal-away", "tied-rim"};

const char *survey_family_name(int family)
{
    return family >= 0 && family < SURVEY_FAMILIES ? family_names[family] : "?";
}

/* xorshift64 in [0, 1): the generator the survey blocks were first drawn with (the tests' reference
 * errors depend on these exact doubles) */
static double next_unit(unsigned long long *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

static void spread_block(int family, double spread, double n[16][3])
{
    unsigned long long s = 88172645463325252ULL + 1000003ULL * (unsigned)(family * 100) +
                           (unsigned long long)(spread * 1e6);
    double phi = 2 * M_PI * next_unit(&s), h = 0.05 + 0.9 * next_unit(&s), rho = sqrt(1 - h * h);
    double cx = rho * cos(phi), cy = rho * sin(phi), cz = -h;
    for (int p = 0; p < 16; ++p) {
        double fa = phi + spread * (p / 15.0 - 0.5);
        if (family == SURVEY_AWAY_ARC) {
            n[p][0] = rho * cos(fa), n[p][1] = rho * sin(fa), n[p][2] = -h;
        } else if (family == SURVEY_RIM_ARC) {
            n[p][0] = cos(fa), n[p][1] = sin(fa), n[p][2] = 0.0;
        } else if (family == SURVEY_HALF_AWAY_ARC) {
            n[p][0] = rho * cos(fa), n[p][1] = rho * sin(fa), n[p][2] = p % 2 ? -h : h;
        } else if (family == SURVEY_RIM_JITTER) {
            n[p][0] = cos(fa), n[p][1] = sin(fa), n[p][2] = p % 3 ? 0.0 : 0.01 * (next_unit(&s) - 0.5);
        } else if (family == SURVEY_BELOW_RIM) {
            double hh = 0.02 * next_unit(&s) * (1 + spread);
            n[p][0] = sqrt(1 - hh * hh) * cos(fa), n[p][1] = sqrt(1 - hh * hh) * sin(fa), n[p][2] = -hh;
        } else if (family == SURVEY_AZIMUTH) {
            double hh = h * (1 + spread * (next_unit(&s) - 0.5) * 0.5);
            hh = hh > 1 ? 1 : hh;
            double r = sqrt(1 - hh * hh);
            n[p][0] = r * cos(phi), n[p][1] = r * sin(phi), n[p][2] = -hh;
        } else { /* the cones: radius spread around (cx, cy, cz), in the frame u (azimuthal), w = c x u */
            double a = spread * sqrt(next_unit(&s)), b = 2 * M_PI * next_unit(&s);
            double ux = -sin(phi), uy = cos(phi), uz = 0;
            double wx = cy * uz - cz * uy, wy = cz * ux - cx * uz, wz = cx * uy - cy * ux;
            n[p][0] = cos(a) * cx + sin(a) * (cos(b) * ux + sin(b) * wx);
            n[p][1] = cos(a) * cy + sin(a) * (cos(b) * uy + sin(b) * wy);
            n[p][2] = cos(a) * cz + sin(a) * (cos(b) * uz + sin(b) * wz);
        }
    }
}

static void fixed_block(int family, double n[16][3])
{
    static const double axes[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    const double tz = sqrt(1 - 0.13); /* the tilted normal (0.3, -0.2, +-tz) */
    for (int p = 0; p < 16; ++p) {
        double *v = n[p];
        if (family == SURVEY_FLAT)
            v[0] = 0, v[1] = 0, v[2] = 1;
        else if (family == SURVEY_EQUAL)
            v[0] = 0.3, v[1] = -0.2, v[2] = tz;
        else if (family == SURVEY_DOWN)
            v[0] = 0, v[1] = 0, v[2] = -1;
        else if (family == SURVEY_EQUAL_AWAY)
            v[0] = 0.3, v[1] = -0.2, v[2] = -tz;
        else
            v[0] = axes[p % 4][0], v[1] = axes[p % 4][1], v[2] = 0;
    }
}

void survey_block(int family, double spread, double n[16][3])
{
    if (family < SURVEY_SPREAD_FAMILIES)
        spread_block(family, spread, n);
    else
        fixed_block(family, n);
}

int survey_block_count(void)
{
    return SURVEY_SPREAD_FAMILIES * SURVEY_SPREADS + (SURVEY_FAMILIES - SURVEY_SPREAD_FAMILIES);
}

void survey_block_at(int i, int *family, double *spread)
{
    const int spread_blocks = SURVEY_SPREAD_FAMILIES * SURVEY_SPREADS;
    if (i < spread_blocks) {
        *family = i / SURVEY_SPREADS;
        *spread = survey_spreads[i % SURVEY_SPREADS];
    } else {
        *family = SURVEY_SPREAD_FAMILIES + (i - spread_blocks);
        *spread = 0.0;
    }
}
