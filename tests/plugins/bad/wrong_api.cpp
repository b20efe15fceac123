// A plugin built for another API version: refused before it is created.
#include "paintlab/plugins/plugin.h"

PAINTLAB_PLUGIN_EXPORT int paintlab_plugin_api_version() { return 999; }
PAINTLAB_PLUGIN_EXPORT paintlab::plugins::Plugin* paintlab_plugin_create() { return nullptr; }
