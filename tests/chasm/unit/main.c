/* chasm_unit_tests: the C unit tests of libchasm on the shared harness
 * (tests/harness/unit.h, plan_test.h), linked with --wrap=malloc & co. so
 * that a test can prove chasm_step() never allocates (unit_alloc.h).
 *
 *   chasm_unit_tests --plugins DIR [--list] [NAME] */
#include "../../harness/plan_test.h"

extern const unit_test semantics_tests[], plugin_tests[], stream_tests[], schema_tests[], structure_tests[];

int main(int argc, char **argv)
{
    unit_register_list(semantics_tests);
    unit_register_list(plugin_tests);
    unit_register_list(stream_tests);
    unit_register_list(schema_tests);
    unit_register_list(structure_tests);
    return unit_main(argc, argv, pt_log_clear);
}
