// A plugin without paintlab_plugin_create: refused.
#include "paintlab/plugins/plugin.h"

PAINTLAB_PLUGIN_EXPORT int paintlab_plugin_api_version() { return paintlab::plugins::kApiVersion; }
