/* A shared object without the `chasm_plugin` symbol. */
int chasm_plugin_v0 = 1;
