// The spectrum table (ingredients.h, spectrum_rows.h): rows written and read
// with their provenance, named spectra, and one spectrum by id. An
// ingredient's own spectra are written and read with it (ingredients.cpp).

#include "spectrum_rows.h"

#include "paintlab/database/ingredients.h"

#include "sqlite.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace paintlab::db {

using detail::Connection;
using detail::Statement;
using detail::Transaction;

std::int64_t addSpectrum(Database& db, std::string_view quantity, const Spectrum& spectrum,
                         const SpectrumInfo& info) {
    const Connection& c = db.impl().connection;
    if (quantity.empty()) throw InputError(c.file().string(), "spectrum.quantity", "the quantity is empty");
    Transaction transaction(c, Transaction::Mode::Write);
    const std::int64_t id = detail::insertSpectrum(c, quantity, spectrum, info);
    transaction.commit();
    return id;
}

std::int64_t addNamedSpectrum(Database& db, std::string_view name, std::string_view quantity,
                              const Spectrum& spectrum, const SpectrumInfo& info) {
    const Connection& c = db.impl().connection;
    if (name.empty()) throw InputError(c.file().string(), "spectrum.name", "the name is empty");
    if (quantity.empty())
        throw InputError(c.file().string(), "spectrum '" + std::string(name) + "'.quantity",
                         "the quantity is empty");
    Transaction transaction(c, Transaction::Mode::Write);
    Statement taken(c, "SELECT id FROM spectrum WHERE name = ?1");
    taken.bind(1, name);
    if (taken.step())
        throw InputError(c.file().string(), "spectrum '" + std::string(name) + "'",
                         "a spectrum with this name already exists (id " + std::to_string(taken.integer(0)) +
                             ")");
    const std::int64_t id = detail::insertSpectrum(c, quantity, spectrum, info);
    Statement set_name(c, "UPDATE spectrum SET name = ?2 WHERE id = ?1");
    set_name.bind(1, id).bind(2, name).run();
    transaction.commit();
    return id;
}

std::optional<StoredSpectrum> findNamedSpectrum(Database& db, std::string_view name) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, "SELECT id FROM spectrum WHERE name = ?1");
    s.bind(1, name);
    std::optional<StoredSpectrum> out;
    if (s.step()) out = detail::selectSpectrum(c, s.integer(0));
    transaction.commit();
    return out;
}

std::vector<StoredSpectrum> namedSpectra(Database& db) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    Statement s(c, "SELECT id FROM spectrum WHERE name IS NOT NULL ORDER BY name");
    std::vector<StoredSpectrum> out;
    while (s.step()) out.push_back(detail::selectSpectrum(c, s.integer(0)));
    transaction.commit();
    return out;
}

StoredSpectrum readSpectrum(Database& db, std::int64_t id) {
    const Connection& c = db.impl().connection;
    Transaction transaction(c, Transaction::Mode::Read);
    auto stored = detail::selectSpectrum(c, id);
    transaction.commit();
    return stored;
}

namespace detail {

std::int64_t insertSpectrum(const Connection& connection, std::string_view quantity, const Spectrum& spectrum,
                            const SpectrumInfo& info) {
    Statement s(connection, "INSERT INTO spectrum (quantity, unit, wavelengths_nm, spectrum_values, source, "
                            "data_date) VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
    // nlohmann writes doubles with max_digits10 digits: they read back exactly.
    s.bind(1, quantity)
        .bind(2, info.unit)
        .bind(3, nlohmann::json(spectrum.wavelengthsNm()).dump())
        .bind(4, nlohmann::json(spectrum.values()).dump())
        .bind(5, info.source)
        .bind(6, info.date)
        .run();
    return connection.lastInsertId();
}

StoredSpectrum selectSpectrum(const Connection& connection, std::int64_t id) {
    Statement s(connection, "SELECT quantity, unit, wavelengths_nm, spectrum_values, source, data_date, "
                            "coalesce(name, '') FROM spectrum WHERE id = ?1");
    s.bind(1, id);
    if (!s.step())
        throw InputError(connection.file().string(), "spectrum " + std::to_string(id), "no such spectrum");
    StoredSpectrum out;
    out.id = id;
    out.quantity = s.text(0);
    out.info = {s.text(1), s.text(4), s.text(5)};
    out.name = s.text(6);
    try {
        const auto wavelengths = nlohmann::json::parse(s.text(2)).get<std::vector<double>>();
        const auto values = nlohmann::json::parse(s.text(3)).get<std::vector<double>>();
        out.spectrum = Spectrum(wavelengths, values);
    } catch (const std::exception& e) {
        throw DatabaseError(connection.file(), DatabaseError::Reason::Corrupt,
                            "spectrum " + std::to_string(id) + " is not a valid spectrum: " + e.what());
    }
    return out;
}

}  // namespace detail

}  // namespace paintlab::db
