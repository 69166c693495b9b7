/* d1_gbuffer_sizes - claim D1: bits per pixel of the G-buffer layouts the talk compares,
 * computed from explicit per-target format tables (src/pipeline/gbuffer_layout.c), and what they
 * cost per frame at 1280x720 with and without 4x MSAA. */
#include "exp_harness.h"
#include "sol_pipeline.h"

#include <stdio.h>
#include <string.h>

static unsigned layout_bits(sol_gbuffer_kind kind, const sol_gbuffer_layout **layout)
{
    unsigned bits = 0;
    exp_check(sol_gbuffer_layout_get(kind, layout), "layout %d", (int)kind);
    exp_check(sol_gbuffer_bits_per_pixel(*layout, &bits), "bits of %s", (*layout)->name);
    return bits;
}

static double frame_mib(const sol_gbuffer_layout *layout, int samples)
{
    uint64_t bytes = 0;
    exp_check(sol_gbuffer_bytes(layout, 1280, 720, samples, &bytes), "bytes of %s", layout->name);
    return (double)bytes / (1024.0 * 1024.0);
}

static void target_table(const exp_run *exp)
{
    exp_table *t = exp_table_new("G-buffer layouts, target by target (D1)", "layout,target,format,bits,contents");
    for (int k = 0; k < SOL_GBUFFER_KIND_COUNT; ++k) {
        const sol_gbuffer_layout *layout;
        layout_bits((sol_gbuffer_kind)k, &layout);
        for (int i = 0; i < layout->target_count; ++i)
            exp_table_row(t, "%s|RT%d|%s|%u|%s", layout->name, i, sol_pixel_format_name(layout->targets[i].format),
                          sol_pixel_format_bits(layout->targets[i].format), layout->targets[i].contents);
    }
    exp_table_write(t, exp, "targets");
}

int main(int argc, char **argv)
{
    exp_run exp;
    exp_init(&exp, "d1_gbuffer_sizes", argc, argv);
    if (exp.bench) /* nothing here has an accuracy knob */
        return 0;
    target_table(&exp);
    exp_table *t = exp_table_new("G-buffer size per layout (D1)",
                                 "layout,bits per pixel,MiB per 1280x720 frame,MiB with 4x MSAA,source of the formats");
    unsigned bits[SOL_GBUFFER_KIND_COUNT];
    for (int k = 0; k < SOL_GBUFFER_KIND_COUNT; ++k) {
        const sol_gbuffer_layout *layout;
        bits[k] = layout_bits((sol_gbuffer_kind)k, &layout);
        exp_table_row(t, "%s|%u|%.2f|%.2f|%s", layout->name, bits[k], frame_mib(layout, 1), frame_mib(layout, 4),
                      layout->source);
    }
    exp_table_write(t, &exp, "sizes");
    {
        const sol_gbuffer_layout *cry;
        exp_number(&exp, "D1-cryengine3-bpp", "%u", layout_bits(SOL_GBUFFER_CRYENGINE3, &cry));
        exp_number(&exp, "D1-cryengine3-msaa4-mib", "%.0f", frame_mib(cry, 4));
    }
    exp_plot(&exp, "sizes",
             "set datafile separator comma\nset style fill solid 0.6\nset boxwidth 0.6\nset ylabel 'bits per pixel'\n"
             "set yrange [0:*]\nset xrange [-0.6:3.6]\nset xtics rotate by -15 font ',8'\nset rmargin 12\nset bmargin 6\nset grid ytics\n"
             "plot 'sizes.csv' using 0:2:xtic(1) with boxes notitle, '' using 0:($2+5):2 with labels notitle");

    char sol_figure[128];
    snprintf(sol_figure, sizeof sol_figure, "%u-%u; %u; %u bits/pixel", bits[SOL_GBUFFER_CLASSIC_NARROW],
             bits[SOL_GBUFFER_CLASSIC_WIDE], bits[SOL_GBUFFER_LIGHT_PREPASS], bits[SOL_GBUFFER_CRYENGINE3]);
    int agrees = bits[SOL_GBUFFER_CLASSIC_NARROW] == 112 && bits[SOL_GBUFFER_CLASSIC_WIDE] == 144 &&
                 bits[SOL_GBUFFER_LIGHT_PREPASS] == 96 && bits[SOL_GBUFFER_CRYENGINE3] == 64;
    exp_claim(&exp, "D1", "112-144; 96 (best case); 64 bits/pixel", sol_figure, "exact",
              agrees ? EXP_REPRODUCED : EXP_NOT_REPRODUCED,
              "sums of the targets' format sizes; CryENGINE 3 and light pre-pass formats follow the talk, the "
              "classic layout's formats are assumed (the talk lists only its attributes): 8-bit vs half-float "
              "normals span the range");
    return 0;
}
