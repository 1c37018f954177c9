// Chi-square gates and the nav config file: values, and errors that say
// file:line:col what is wrong.
#include <cmath>
#include <string>
#include <vector>

#include "../../harness/unit.h"
#include "nav/chi2.hpp"
#include "nav/nav_config.hpp"

TEST(chi2_quantiles_match_tables)
{
    // published chi-square table values
    CHECK_NEAR(nav::chi2_quantile(1, 0.95), 3.841, 1e-3);
    CHECK_NEAR(nav::chi2_quantile(2, 0.95), 5.991, 1e-3);
    CHECK_NEAR(nav::chi2_quantile(3, 0.95), 7.815, 1e-3);
    CHECK_NEAR(nav::chi2_quantile(1, 0.999), 10.828, 1e-3);
    CHECK_NEAR(nav::chi2_quantile(2, 0.999), 13.816, 1e-3);
    CHECK_NEAR(nav::chi2_quantile(3, 0.999), 16.266, 1e-3);
    CHECK(std::isnan(nav::chi2_quantile(4, 0.9)));
    CHECK(std::isnan(nav::chi2_quantile(1, 1.0)));
}

TEST(config_reads_keys_transponders_and_derives_gates)
{
    nav::NavConfig c;
    std::vector<std::string> errors;
    const bool ok = nav::parse_config("t.nav",
                                      "# comment\n"
                                      "compass_noise_rad 0.01   # trailing comment\n"
                                      "gate_probability 0.95\n"
                                      "reset_after_gps 7\n"
                                      "aid_window_lbl_s 45\n"
                                      "initial_north_m -12.5\n"
                                      "transponder 4 100 -50.5 38 0.05\n"
                                      "transponder 9 0 0 10 0\n",
                                      c, errors);
    CHECK(ok && errors.empty());
    CHECK_NEAR(c.compass_noise_rad, 0.01, 0);
    CHECK_NEAR(c.gate_chi2[2], 5.991, 1e-3);
    CHECK(c.reset_after[nav::SENSOR_GPS] == 7);
    CHECK_NEAR(c.aid_window_s[nav::SENSOR_LBL], 45, 0);
    CHECK(c.have_initial_position);
    CHECK_NEAR(c.initial_north_m, -12.5, 0);
    CHECK(c.n_transponders == 2);
    const nav::Transponder *t = c.transponder(4);
    CHECK(t && t->east_m == -50.5 && t->turnaround_s == 0.05);
    CHECK(c.transponder(5) == nullptr);
}

TEST(config_errors_name_file_line_and_column)
{
    nav::NavConfig c;
    std::vector<std::string> errors;
    const bool ok = nav::parse_config("bad.nav",
                                      "compas_noise_rad 0.01\n"
                                      "depth_noise_m abc\n"
                                      "  gate_probability 2\n"
                                      "reset_after_dvl 2.5\n"
                                      "transponder 1 0 0 10\n"
                                      "transponder 2 0 0 10 0.1\n"
                                      "transponder 2 5 5 10 0.1\n"
                                      "dvl_noise_mps\n"
                                      "gps_noise_m 1 2\n",
                                      c, errors);
    CHECK(!ok);
    CHECK(errors.size() == 8);
    if (errors.size() != 8)
        return;
    CHECK_STR(errors[0].c_str(), "bad.nav:1:1: unknown key 'compas_noise_rad' (did you mean 'compass_noise_rad'?)");
    CHECK_STR(errors[1].c_str(), "bad.nav:2:15: 'abc' is not a number");
    CHECK_STR(errors[2].c_str(), "bad.nav:3:20: gate_probability = 2 is outside 0.5 .. 1");
    CHECK_STR(errors[3].c_str(), "bad.nav:4:17: 'reset_after_dvl' must be an integer");
    CHECK_STR(errors[4].c_str(), "bad.nav:5:1: transponder needs 5 values: ID NORTH_M EAST_M DEPTH_M TURNAROUND_S");
    CHECK_STR(errors[5].c_str(), "bad.nav:7:13: transponder 2 is defined twice");
    CHECK_STR(errors[6].c_str(), "bad.nav:8:14: 'dvl_noise_mps' needs a value");
    CHECK_STR(errors[7].c_str(), "bad.nav:9:15: 'gps_noise_m' takes one value");
}

TEST(config_file_that_is_missing_is_an_error)
{
    nav::NavConfig c;
    std::vector<std::string> errors;
    CHECK(!nav::load_config("/nonexistent/x.nav", c, errors));
    CHECK(errors.size() == 1 && errors[0].find("/nonexistent/x.nav: cannot open") == 0);
}
