#pragma once
// One ingredient as a JSON object of the ingredient file format
// (ingredient_json.h), for the other file formats that are built on it
// (ingredient_csv.cpp). Private to the database library.

#include "paintlab/database/ingredients.h"

#include <nlohmann/json.hpp>

#include <string>

namespace paintlab::db::detail {

// Throws InputError(source, field + "." + key, ...) for every structural problem.
Ingredient ingredientFromJson(const nlohmann::json& json, const std::string& field,
                              const std::string& source);
nlohmann::ordered_json ingredientToJson(const Ingredient& ingredient);

}  // namespace paintlab::db::detail
