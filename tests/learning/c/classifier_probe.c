/*
 * Classifier probe (test code): initial fit on the study's two points, then for each sample
 * of a stream print the decision ('0'/'1') before learning from it, then the decisions on a
 * grid, then the weights and intercept as raw IEEE bits. The data come from probe_data.h,
 * written by tests/learning/test_c_classifier.py.
 */
#include "swarmvm_learn.h"
#include "probe_io.h"
#include "probe_data.h"

static svl_classifier_t model;

int main(void)
{
    static const svl_real mean[3] = {3500.0, 2.75, 50.0};
    static const svl_real scale[3] = {1443.38, 1.299, 28.87};
    static const svl_real seed_points[6] = {1000.0, 0.5, 100.0, 6000.0, 5.0, 0.0};
    static const uint8_t seed_labels[2] = {1, 0};
    svl_real x[3];
    uint16_t i, epochs;
    uint8_t a, b, c;
    probe_start();
    svl_classifier_init(&model, 3, mean, scale, (svl_real)0.01);
    epochs = svl_classifier_fit(&model, seed_points, seed_labels, 2, 1000, (svl_real)1e-3, 5);
    probe_puts("E ");
    probe_hex(&epochs, 2);
    probe_puts("\nS ");
    for (i = 0; i < PROBE_STREAM; i++) {
        svl_real row[4];
        PROBE_READ(row, probe_stream[i], sizeof row);
        x[0] = row[0];
        x[1] = row[1];
        x[2] = row[2];
        probe_putc(svl_classifier_decide(&model, x) ? '1' : '0');
        svl_classifier_partial_fit(&model, x, row[3] > 0.5);
    }
    probe_puts("\nG ");
    for (a = 0; a < PROBE_GRID; a++) {
        for (b = 0; b < PROBE_GRID; b++) {
            for (c = 0; c < PROBE_GRID; c++) {
                x[0] = (svl_real)(1000.0 + 5000.0 * a / (PROBE_GRID - 1));
                x[1] = (svl_real)(0.5 + 4.5 * b / (PROBE_GRID - 1));
                x[2] = (svl_real)(100.0 * c / (PROBE_GRID - 1));
                probe_putc(svl_classifier_decide(&model, x) ? '1' : '0');
            }
        }
    }
    probe_puts("\nW");
    for (a = 0; a < 3; a++) {
        probe_putc(' ');
        probe_hex(&model.w[a], sizeof(svl_real));
    }
    probe_putc(' ');
    probe_hex(&model.intercept, sizeof(svl_real));
    probe_puts("\nEND\n");
    probe_end();
    return 0;
}
