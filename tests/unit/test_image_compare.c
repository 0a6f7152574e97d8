/* il_image_compare on hand-made images with known answers. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "illum/illum.h"

static il_image make(uint32_t w, uint32_t h, const float *rgb)
{
    il_image im = {0};
    il_error err = {0};
    CHECK_OK(il_image_alloc(&im, w, h, &err), &err);
    memcpy(im.rgb, rgb, (size_t)w * h * 3 * sizeof(float));
    return im;
}

static void test_known_answer(void)
{
    /* a - b per channel: 0 1 2 | 0 0 -1 */
    const float av[] = {1, 2, 3, 0, 0, 0};
    const float bv[] = {1, 1, 1, 0, 0, 1};
    il_image a = make(2, 1, av), b = make(2, 1, bv), diff = {0};
    il_error err = {0};
    il_compare_result r;
    CHECK_OK(il_image_compare(&a, &b, &r, &diff, &err), &err);
    /* squared errors 0 1 4 0 0 1: mean 1 */
    CHECK_NEAR(r.rmse, 1.0, 1e-12);
    /* (1 + 4 + 1) / (1 + 0.01) over 6 channels; zero errors add nothing */
    CHECK_NEAR(r.rel_mse, (6.0 / 1.01) / 6.0, 1e-12);
    /* Rec.709 luminance: a = (0.2126 + 2*0.7152 + 3*0.0722, 0) -> mean 0.9298 */
    CHECK_NEAR(r.mean_lum_a, 0.9298, 1e-6);
    /* b = (1, 0.0722) -> mean 0.5361 */
    CHECK_NEAR(r.mean_lum_b, 0.5361, 1e-6);
    CHECK_NEAR(r.max_abs_error, 2.0, 0.0);
    CHECK(diff.width == 2 && diff.height == 1);
    const float want[] = {0, 1, 2, 0, 0, 1};
    for (int i = 0; i < 6; i++)
        CHECK_NEAR(diff.rgb[i], want[i], 0.0);
    il_image_free(&diff);

    /* The reference matters for rel_mse: swap roles. */
    CHECK_OK(il_image_compare(&b, &a, &r, NULL, &err), &err);
    CHECK_NEAR(r.rmse, 1.0, 1e-12);
    CHECK_NEAR(r.rel_mse, (1.0 / 4.01 + 4.0 / 9.01 + 1.0 / 0.01) / 6.0, 1e-12);

    /* Identical images: every error is zero. */
    CHECK_OK(il_image_compare(&a, &a, &r, NULL, &err), &err);
    CHECK(r.rmse == 0.0 && r.rel_mse == 0.0 && r.max_abs_error == 0.0);
    CHECK_NEAR(r.mean_lum_a, r.mean_lum_b, 0.0);
    il_image_free(&a);
    il_image_free(&b);
}

static void test_relative_epsilon(void)
{
    /* One channel off by 0.1 on a reference of 0.1: 0.01 / (0.01 + 0.01) = 0.5,
     * averaged over 3 channels. */
    const float av[] = {0.2f, 0.1f, 0.1f};
    const float bv[] = {0.1f, 0.1f, 0.1f};
    il_image a = make(1, 1, av), b = make(1, 1, bv);
    il_error err = {0};
    il_compare_result r;
    CHECK_OK(il_image_compare(&a, &b, &r, NULL, &err), &err);
    CHECK_NEAR(r.rel_mse, 0.5 / 3.0, 1e-6);
    CHECK_NEAR(r.rmse, sqrt(0.01 / 3.0), 1e-7);
    CHECK_NEAR(r.max_abs_error, 0.1, 1e-7);
    il_image_free(&a);
    il_image_free(&b);
}

static void test_nonfinite(void)
{
    const float av[] = {1, NAN, 1, 1, 1, 1};
    const float bv[] = {1, 1, 1, 1, 1, INFINITY};
    const float cv[] = {1, 1, 1, 1, 1, 1};
    il_image a = make(2, 1, av), b = make(2, 1, bv), c = make(2, 1, cv), diff = {0};
    il_error err = {0};
    il_compare_result r;
    /* NaN in the test image cannot hide: every error metric is +Inf. */
    CHECK_OK(il_image_compare(&a, &c, &r, &diff, &err), &err);
    CHECK(isinf(r.rmse) && r.rmse > 0);
    CHECK(isinf(r.rel_mse) && r.rel_mse > 0);
    CHECK(isinf(r.max_abs_error) && r.max_abs_error > 0);
    CHECK(isinf(diff.rgb[1]) && diff.rgb[1] > 0);
    CHECK(diff.rgb[0] == 0.0f && diff.rgb[5] == 0.0f);
    CHECK(isnan(r.mean_lum_a));
    CHECK_NEAR(r.mean_lum_b, 1.0, 1e-9);
    il_image_free(&diff);
    /* Inf in the reference too. */
    CHECK_OK(il_image_compare(&c, &b, &r, NULL, &err), &err);
    CHECK(isinf(r.max_abs_error) && isinf(r.rmse));
    il_image_free(&a);
    il_image_free(&b);
    il_image_free(&c);
}

static void test_errors(void)
{
    const float v[12] = {0};
    il_image a = make(2, 2, v), b = make(4, 1, v), empty = {0}, diff = {0};
    il_error err = {0};
    il_compare_result r;
    CHECK(il_image_compare(&a, &b, &r, &diff, &err) == IL_ERR_INVALID);
    CHECK(err.status == IL_ERR_INVALID && strstr(err.message, "2x2") != NULL);
    CHECK(diff.rgb == NULL);
    CHECK(il_image_compare(&a, &empty, &r, NULL, &err) == IL_ERR_INVALID);
    CHECK(il_image_compare(NULL, &a, &r, NULL, &err) == IL_ERR_INVALID);
    il_image_free(&a);
    il_image_free(&b);
}

int main(void)
{
    test_known_answer();
    test_relative_epsilon();
    test_nonfinite();
    test_errors();
    return check_report();
}
