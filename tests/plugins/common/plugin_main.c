/* main of every test_plugin_NAME: runs the plugin's list (plugin_test.h). */
#include "plugin_test.h"

int main(int argc, char **argv)
{
    unit_register_list(plugin_tests);
    return unit_main(argc, argv, pt_log_clear);
}
