#pragma once
// What the `db` command files share (db_commands.cpp, db_exchange_commands.cpp).

#include "commands.h"

#include "paintlab/database/database.h"

#include <CLI/CLI.hpp>

#include <string>

namespace paintlab::cli {

// The database of --db FILE (which must exist unless create), or the user's
// default one, filled from the demo data on first use.
db::Database openCliDatabase(const std::string& db_file, bool create);

// `db import|export|recipe-export|production|measurement-import|measurements|spectra`.
void addDbExchangeCommands(CLI::App& group, CommandAction& action);

}  // namespace paintlab::cli
