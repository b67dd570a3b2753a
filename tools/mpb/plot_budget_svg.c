/*
 * plot_budget_svg.c - success against the time budget as inline SVG, for
 * the HTML report: the curves plot_budget.c reads, drawn without gnuplot
 * (plot.h). Log time axis from below the first solution to the time
 * limit; per configuration a step curve of the fraction of its runs
 * verified by t (solid) and claimed by t (dotted).
 */
#include <math.h>
#include <stdio.h>

#include "plot.h"
#include "view.h"

#define W 600
#define H 300
#define LEFT 50
#define RIGHT 230       /* the legend: names of about 30 characters */
#define TOP 14
#define BOTTOM 40

typedef struct axes {
    double lo, hi;      /* time range, s */
} axes;

static double px(const axes *a, double t)
{
    double f = (log10(fmax(t, a->lo)) - log10(a->lo)) /
               (log10(a->hi) - log10(a->lo));
    return LEFT + fmin(fmax(f, 0.0), 1.0) * (W - LEFT - RIGHT);
}

static double py(double fraction)
{
    return TOP + (1.0 - fraction) * (H - TOP - BOTTOM);
}

/* One step curve: from (lo, 0) up a step at each time, on to the limit. */
static void steps(FILE *out, const axes *a, const double *t, int n, int runs,
                  const char *cls, const char *color, const char *name)
{
    fprintf(out, "<path class=\"curve %s\" data-planner=\"", cls);
    view_html_text(out, name);
    fprintf(out, "\" fill=\"none\" stroke=\"%s\" stroke-width=\"%s\"%s d=\"M%.1f %.1f",
            color, cls[0] == 'v' ? "2" : "1.5",
            cls[0] == 'v' ? "" : " stroke-dasharray=\"2 3\"", px(a, a->lo),
            py(0));
    for (int j = 0; j < n; j++) {
        if (j + 1 < n && t[j + 1] == t[j])
            continue;
        fprintf(out, "H%.1fV%.1f", px(a, t[j]), py((double)(j + 1) / runs));
    }
    fprintf(out, "H%.1f\"/>\n", px(a, a->hi));
}

int plot_budget_svg(FILE *out, const plot_budget *b, int set)
{
    int nc = plot_budget_num_configs(b), any = 0, paths = 0;
    axes a = {INFINITY, plot_budget_limit(b) > 0 ? plot_budget_limit(b) : 1.0};
    for (int c = 0; c < nc; c++) {
        plot_budget_steps k;
        plot_budget_curve(b, set, c, &k);
        any |= k.runs > 0;
        if (k.nv > 0)
            a.lo = fmin(a.lo, k.verified[0]);
        if (k.nc > 0)
            a.lo = fmin(a.lo, k.claimed[0]);
    }
    if (!any)
        return 0;
    /* As gnuplot's: half the first solution, at least 1 us. */
    a.lo = isfinite(a.lo) ? fmax(a.lo / 2, 1e-6) : a.hi / 1000;
    if (!(a.lo < a.hi))
        a.lo = a.hi / 1000;
    fprintf(out, "<figure><svg class=\"budget\" "
            "viewBox=\"0 0 %d %d\" width=\"%d\" height=\"%d\" role=\"img\">"
            "<title>", W, H, W, H);
    view_html_text(out, plot_budget_set(b, set));
    fputs(": runs solved within the time budget</title>\n", out);
    /* Grid and axes: decades, fractions by 0.25. */
    fputs("<g stroke=\"#dddddd\" font-size=\"11\" fill=\"#1d2433\">\n", out);
    for (double d = pow(10, ceil(log10(a.lo) - 1e-9)); d <= a.hi * (1 + 1e-9);
         d *= 10) {
        double x = px(&a, d);
        fprintf(out, "<line x1=\"%.1f\" y1=\"%d\" x2=\"%.1f\" y2=\"%d\"/>"
                "<text x=\"%.1f\" y=\"%d\" text-anchor=\"middle\" "
                "stroke=\"none\">%g</text>\n", x, TOP, x, H - BOTTOM, x,
                H - BOTTOM + 14, d);
    }
    for (int i = 0; i <= 4; i++) {
        double y = py(i / 4.0);
        fprintf(out, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\"/>"
                "<text x=\"%d\" y=\"%.1f\" text-anchor=\"end\" "
                "stroke=\"none\">%.2g</text>\n", LEFT, y, W - RIGHT, y,
                LEFT - 4, y + 4, i / 4.0);
    }
    fprintf(out, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\" stroke=\"none\">"
            "time budget t (s, log); solid: verified, dotted: claimed"
            "</text>\n</g>\n", (LEFT + W - RIGHT) / 2, H - 8);
    for (int c = 0; c < nc; c++) {
        plot_budget_steps k;
        plot_budget_curve(b, set, c, &k);
        if (k.runs == 0)
            continue;
        const char *color = plot_config_color(c), *name = plot_budget_config(b, c);
        steps(out, &a, k.verified, k.nv, k.runs, "verified", color, name);
        steps(out, &a, k.claimed, k.nc, k.runs, "claimed", color, name);
        paths += 2;
        int y = TOP + 8 + 16 * (paths / 2 - 1);
        fprintf(out, "<line x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\" stroke=\"%s\" "
                "stroke-width=\"2\"/><text x=\"%d\" y=\"%d\" font-size=\"11\">",
                W - RIGHT + 10, y, W - RIGHT + 28, y, color, W - RIGHT + 32,
                y + 4);
        view_html_text(out, name);
        fprintf(out, " %.0f%%</text>\n", 100.0 * k.nv / k.runs);
    }
    fputs("</svg><figcaption>", out);
    view_html_text(out, plot_budget_set(b, set));
    fputs("</figcaption></figure>\n", out);
    return paths;
}
