/* ringing — Green (2003) notes that his 4-band reconstruction grows "fins":
 * negative lobes from truncating a function with kinks, and recommends
 * windowing.  For Green's light and a 30° cap we measure, per order, the
 * most negative value of the reconstruction and the fraction of ∫f² that lies
 * where f < 0, without a window and with Gaussian, Hann and Lanczos windows
 * (sh_window_factor), and render the reconstructions as images. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "exp.h"

static void write_matrix(const char *name, const char *title, const sh_image *img)
{
    FILE *f = exp_data(name, title, "gnuplot matrix: rows = image rows (theta from 0 at top), columns = phi");
    for (int j = 0; j < img->height; j++) {
        for (int i = 0; i < img->width; i++) fprintf(f, "%s%.6g", i ? " " : "", img->data[(size_t)j * img->width + i]);
        fputc('\n', f);
    }
    fclose(f);
}

static void gauss_window(int order, sh_window *w)
{
    /* factor exp(-S l(l+1)) = 0.1 at l = order-1 */
    w->kind = SH_WINDOW_GAUSS;
    w->param = log(10.0) / ((double)order * (order - 1 > 0 ? order - 1 : 1));
}

int main(int argc, char **argv)
{
    exp_init(argc, argv);
    const char *specs[2] = {"green", "cap:30"};
    const char *labels[2] = {"Green's light", "cap 30°"};
    const int maxo = 16, width = 256;
    double *c = malloc(sizeof(double) * maxo * maxo);
    FILE *f = exp_data("ringing.dat", "ringing of truncated reconstructions",
                       "order light(0=green,1=cap30) window(0=none,1=gauss,2=hann,3=lanczos) most_negative negative_energy_fraction");
    double green4[4][2];
    for (int s = 0; s < 2; s++) {
        sh_light L;
        exp_check(sh_light_parse(specs[s], 1, &L), "light");
        for (int order = 2; order <= maxo; order++) {
            exp_progress("%s order %d", labels[s], order);
            if (sh_light_has_closed_form(&L)) exp_check(sh_light_closed_form(&L, order, SH_CS, c), "closed form");
            else exp_check(sh_green_reference(order, SH_CS, 1e-10, c), "green reference");
            sh_window w[4] = {{SH_WINDOW_NONE, 0}, {SH_WINDOW_GAUSS, 0}, {SH_WINDOW_HANN, order}, {SH_WINDOW_LANCZOS, order}};
            gauss_window(order, &w[1]);
            for (int k = 0; k < 4; k++) {
                double mn, frac;
                exp_check(sh_ringing(order, SH_CS, c, &w[k], width, &mn, &frac), "sh_ringing");
                fprintf(f, "%d %d %d %.6e %.6e\n", order, s, k, mn, frac);
                if (s == 0 && order == 4) { green4[k][0] = mn; green4[k][1] = frac; }
            }
        }
        fprintf(f, "\n\n");
    }
    fclose(f);

    /* images: Green's light, its order-4 reconstruction, windowed (Hann) */
    sh_light green;
    exp_check(sh_light_parse("green", 0, &green), "light");
    sh_image orig;
    exp_check(sh_image_from_fn(SH_LAYOUT_LATLONG, width, width / 2, sh_light_fn, &green, &orig), "image");
    write_matrix("green_original.dat", "Green's light, point samples", &orig);
    sh_image_free(&orig);
    exp_check(sh_green_reference(4, SH_CS, 1e-10, c), "green reference");
    sh_window none = {SH_WINDOW_NONE, 0}, hann = {SH_WINDOW_HANN, 4};
    sh_image r;
    exp_check(sh_reconstruct_latlong(4, SH_CS, c, 1, &none, width, &r), "reconstruct");
    write_matrix("green_order4.dat", "Green's light, order-4 reconstruction", &r);
    sh_image_free(&r);
    exp_check(sh_reconstruct_latlong(4, SH_CS, c, 1, &hann, width, &r), "reconstruct");
    write_matrix("green_order4_hann.dat", "Green's light, order-4 reconstruction, Hann window", &r);
    sh_image_free(&r);
    free(c);

    {
        char me[160];
        snprintf(me, sizeof me, "order 4: most negative %.4f unwindowed, %.4f Gaussian, %.4f Hann, %.4f Lanczos",
                 green4[0][0], green4[1][0], green4[2][0], green4[3][0]);
        const int ok = green4[1][0] > 0.1 * green4[0][0] && green4[2][0] > 0.2 * green4[0][0];
        exp_claim_judged("green-ringing-window", "Green 2003, SH Projection",
                         "the fins (negative lobes) of the 4-band reconstruction are caused by truncation and are removed "
                         "by windowing (Gaussian pre-filtering)",
                         "qualitative", me, "windowed most-negative within 10 % (Gauss) / 20 % (Hann) of unwindowed",
                         ok,
                         "ringing/ringing.dat",
                         "a window leaves negative lobes deeper than the tolerance allows.");
    }
    exp_index("![ringing vs order](ringing.png)\n\n"
              "Most negative value of the truncated reconstruction (negative lobes, Green's \"fins\") for "
              "Green's light and a 30° cap, orders 2–16, without a window and with a Gaussian "
              "(exp(−S l(l+1)), S chosen so the top band keeps 10 %%), Hann and Lanczos windows of width n. "
              "At order 4, Green's light reaches %.4f unwindowed (%.2f %% of ∫f² in negative lobes), %.4f "
              "with the Gaussian, %.4f with Hann and %.4f with Lanczos.\n\n"
              "![Green's light images](ringing_images.png)\n\n"
              "Green's light (point samples), its exact order-4 reconstruction and the Hann-windowed one, as "
              "lat-long images (θ down, φ across); the colour scale is shared and white is zero, so the "
              "fins show as the blue areas.",
              green4[0][0], 100 * green4[0][1], green4[1][0], green4[2][0], green4[3][0]);
    return 0;
}
