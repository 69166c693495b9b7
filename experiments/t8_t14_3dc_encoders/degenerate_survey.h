/* degenerate_survey.h - the constructed hard blocks of issue 13's degenerate-block goal ("flat, all
 * normals equal, all z = -1 or pointing away, z = 0 rims, exactly tied anchors finish in
 * milliseconds with the exact answer"), shared by make bench (bench_degenerate in main.c) and the
 * tests (tests/test_normalmaps.c, which hold reference errors for some of these blocks).
 *
 * Families 0..SURVEY_SPREAD_FAMILIES-1 take a spread (radians) and are seeded per (family, spread);
 * the others are fixed blocks (spread ignored). survey_block_count() blocks in all: every family
 * at every spread of survey_spreads (the spread families) or once. */
#ifndef DEGENERATE_SURVEY_H
#define DEGENERATE_SURVEY_H

enum {
    SURVEY_AWAY_ARC,        /* an arc of normals pointing away (z < 0), one height */
    SURVEY_RIM_ARC,         /* an arc on the rim (z = 0) */
    SURVEY_HALF_AWAY_ARC,   /* an arc, every other pixel pointing away */
    SURVEY_RIM_JITTER,      /* a rim arc, every third pixel a hair above or below z = 0 */
    SURVEY_AWAY_CONE,       /* a cone of normals pointing away */
    SURVEY_AZIMUTH,         /* one azimuth, pointing away, heights varied */
    SURVEY_AWAY_CONE2,      /* a second cone pointing away (another seed) */
    SURVEY_BELOW_RIM,       /* an arc just below the rim */
    SURVEY_SPREAD_FAMILIES, /* the families above take a spread */
    SURVEY_FLAT = SURVEY_SPREAD_FAMILIES, /* every normal (0, 0, 1) */
    SURVEY_EQUAL,           /* every normal the same, tilted */
    SURVEY_DOWN,            /* every normal (0, 0, -1) */
    SURVEY_EQUAL_AWAY,      /* every normal the same, pointing away */
    SURVEY_TIED_RIM,        /* rim normals on the axes (+-1, 0, 0), (0, +-1, 0): exactly tied anchors */
    SURVEY_FAMILIES
};

enum { SURVEY_SPREADS = 7 };
extern const double survey_spreads[SURVEY_SPREADS]; /* radians: 0, 0.01, 0.03, 0.1, 0.3, 1, 2 */

/* The family's name (e.g. "away-cone"), or "?" out of range. */
const char *survey_family_name(int family);

/* The 16 unit normals of a block of `family` (0 <= family < SURVEY_FAMILIES) at `spread`: the same
 * doubles on every run and machine with IEEE doubles and a correctly rounded libm for sqrt (cos and
 * sin as the platform's libm gives them). */
void survey_block(int family, double spread, double n[16][3]);

/* How many blocks the bench visits: SURVEY_SPREAD_FAMILIES * SURVEY_SPREADS + the fixed families. */
int survey_block_count(void);

/* Block i (0 <= i < survey_block_count()) of the bench's order: its family and spread. */
void survey_block_at(int i, int *family, double *spread);

#endif
