-- PaintLab database, schema version 1: ingredients, spectra, recipes with
-- immutable versions, measurements and fits.
--
-- Run by the migration runner (database/src/migrations.cpp) inside one
-- transaction, which then sets PRAGMA user_version = 1. Units are in the
-- column names; every CHECK mirrors a rule of the C++ side so that a row
-- written by another tool (the sqlite3 shell) cannot break the invariants.

-- Marks the file as a PaintLab database ("PLDB"), so another program's
-- SQLite file is refused instead of being migrated.
PRAGMA application_id = 1347175490;

-- A tabulated spectrum (or a constant: one sample). Wavelengths and values
-- are JSON arrays of numbers of equal length; a spectrum belongs to at most
-- one ingredient but may also stand alone (measured spectra).
CREATE TABLE spectrum (
    id             INTEGER PRIMARY KEY,
    quantity       TEXT NOT NULL,               -- what it is: 'refractive_index', 'metal_k', 'albedo', ...
    unit           TEXT NOT NULL,               -- '1' (dimensionless), '1/µm', ...
    wavelengths_nm TEXT NOT NULL CHECK (json_valid(wavelengths_nm) AND json_type(wavelengths_nm) = 'array'),
    spectrum_values TEXT NOT NULL CHECK (json_valid(spectrum_values) AND json_type(spectrum_values) = 'array'),
    source         TEXT NOT NULL DEFAULT '',    -- literature reference, instrument or method
    data_date      TEXT NOT NULL DEFAULT '',    -- when the data were measured or published (ISO 8601 or year)
    created_at     TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    CHECK (json_array_length(wavelengths_nm) = json_array_length(spectrum_values)
           AND json_array_length(spectrum_values) >= 1)
);

-- Every ingredient: the common part. Names are unique within a kind, which
-- is how recipes (whose components carry names) are linked to ingredients.
CREATE TABLE ingredient (
    id             INTEGER PRIMARY KEY,
    kind           TEXT NOT NULL CHECK (kind IN ('binder', 'pigment', 'mirror_flake',
                                                 'interference_flake', 'substrate')),
    name           TEXT NOT NULL CHECK (length(name) > 0),
    description    TEXT NOT NULL DEFAULT '',
    source         TEXT NOT NULL DEFAULT '',
    density_g_cm3  REAL CHECK (density_g_cm3 IS NULL OR density_g_cm3 > 0),
    density_source TEXT NOT NULL DEFAULT '',
    created_at     TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    updated_at     TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    UNIQUE (kind, name)
);
CREATE INDEX ingredient_name ON ingredient (name);

-- Binder / lacquer: the film former.
CREATE TABLE binder (
    ingredient_id              INTEGER PRIMARY KEY REFERENCES ingredient (id) ON DELETE CASCADE,
    refractive_index_spectrum  INTEGER NOT NULL REFERENCES spectrum (id),
    absorption_per_um_spectrum INTEGER NOT NULL REFERENCES spectrum (id)
);

-- Pigment: absorption and scattering per unit volume fraction (1/µm).
CREATE TABLE pigment (
    ingredient_id           INTEGER PRIMARY KEY REFERENCES ingredient (id) ON DELETE CASCADE,
    sigma_a_per_um_spectrum INTEGER NOT NULL REFERENCES spectrum (id),
    sigma_s_per_um_spectrum INTEGER NOT NULL REFERENCES spectrum (id),
    hg_g                    REAL NOT NULL CHECK (hg_g > -1 AND hg_g < 1),
    particle_diameter_um    REAL NOT NULL CHECK (particle_diameter_um > 0)
);

-- Mirror (metal) flake: reflectance spectrum, or the metal's n + ik.
CREATE TABLE mirror_flake (
    ingredient_id          INTEGER PRIMARY KEY REFERENCES ingredient (id) ON DELETE CASCADE,
    reflectance_spectrum   INTEGER REFERENCES spectrum (id),
    metal_n_spectrum       INTEGER REFERENCES spectrum (id),
    metal_k_spectrum       INTEGER REFERENCES spectrum (id),
    diameter_um            REAL NOT NULL CHECK (diameter_um > 0),     -- mean of the diameter distribution
    diameter_sd_um         REAL NOT NULL DEFAULT 0 CHECK (diameter_sd_um >= 0),
    thickness_um           REAL NOT NULL CHECK (thickness_um > 0),
    orientation_spread_deg REAL NOT NULL CHECK (orientation_spread_deg >= 0 AND orientation_spread_deg <= 90),
    CHECK ((reflectance_spectrum IS NOT NULL AND metal_n_spectrum IS NULL AND metal_k_spectrum IS NULL)
        OR (reflectance_spectrum IS NULL AND metal_n_spectrum IS NOT NULL AND metal_k_spectrum IS NOT NULL))
);

-- Interference (pearl) flake: TiO2 / mica / TiO2, thicknesses with their spreads.
CREATE TABLE interference_flake (
    ingredient_id            INTEGER PRIMARY KEY REFERENCES ingredient (id) ON DELETE CASCADE,
    mica_index_spectrum      INTEGER NOT NULL REFERENCES spectrum (id),
    tio2_index_spectrum      INTEGER NOT NULL REFERENCES spectrum (id),
    mica_thickness_nm        REAL NOT NULL CHECK (mica_thickness_nm >= 0),
    mica_thickness_spread_nm REAL NOT NULL CHECK (mica_thickness_spread_nm >= 0),
    tio2_thickness_nm        REAL NOT NULL CHECK (tio2_thickness_nm >= 0),
    tio2_thickness_spread_nm REAL NOT NULL CHECK (tio2_thickness_spread_nm >= 0),
    diameter_um              REAL NOT NULL CHECK (diameter_um > 0),
    diameter_sd_um           REAL NOT NULL DEFAULT 0 CHECK (diameter_sd_um >= 0),
    orientation_spread_deg   REAL NOT NULL CHECK (orientation_spread_deg >= 0 AND orientation_spread_deg <= 90)
);

-- Substrate: the engine's four kinds, with the data each one needs.
CREATE TABLE substrate (
    ingredient_id    INTEGER PRIMARY KEY REFERENCES ingredient (id) ON DELETE CASCADE,
    substrate_kind   TEXT NOT NULL CHECK (substrate_kind IN ('lambertian', 'metal', 'black', 'transparent')),
    albedo_spectrum  INTEGER REFERENCES spectrum (id),
    metal_n_spectrum INTEGER REFERENCES spectrum (id),
    metal_k_spectrum INTEGER REFERENCES spectrum (id),
    refractive_index REAL CHECK (refractive_index IS NULL OR refractive_index >= 1),
    CHECK ((substrate_kind = 'lambertian') = (albedo_spectrum IS NOT NULL)),
    CHECK ((substrate_kind = 'metal') = (metal_n_spectrum IS NOT NULL AND metal_k_spectrum IS NOT NULL)),
    CHECK ((substrate_kind = 'transparent') = (refractive_index IS NOT NULL))
);

CREATE TABLE tag (
    id   INTEGER PRIMARY KEY,
    name TEXT NOT NULL UNIQUE COLLATE NOCASE CHECK (length(name) > 0)
);
CREATE TABLE ingredient_tag (
    ingredient_id INTEGER NOT NULL REFERENCES ingredient (id) ON DELETE CASCADE,
    tag_id        INTEGER NOT NULL REFERENCES tag (id),
    PRIMARY KEY (ingredient_id, tag_id)
) WITHOUT ROWID;
CREATE INDEX ingredient_tag_by_tag ON ingredient_tag (tag_id);

-- What can be made: technological limits of an ingredient in a film.
CREATE TABLE technological_limit (
    ingredient_id       INTEGER PRIMARY KEY REFERENCES ingredient (id) ON DELETE CASCADE,
    max_volume_fraction REAL CHECK (max_volume_fraction IS NULL
                                    OR (max_volume_fraction > 0 AND max_volume_fraction <= 1)),
    min_thickness_um    REAL CHECK (min_thickness_um IS NULL OR min_thickness_um >= 0),
    max_thickness_um    REAL CHECK (max_thickness_um IS NULL OR max_thickness_um > 0),
    CHECK (min_thickness_um IS NULL OR max_thickness_um IS NULL OR min_thickness_um <= max_thickness_um)
);

-- Recipes and their versions. A version is never changed once saved (the
-- triggers below refuse UPDATE and DELETE): editing a recipe saves a new
-- version. recipe_json is the canonical recipe JSON (engine recipe_json.h),
-- the single source of truth; checksum_sha256 is the SHA-256 of its UTF-8
-- bytes, printed on production sheets.
CREATE TABLE recipe (
    id         INTEGER PRIMARY KEY,
    name       TEXT NOT NULL UNIQUE CHECK (length(name) > 0),
    created_at TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
CREATE TABLE recipe_version (
    id              INTEGER PRIMARY KEY,
    recipe_id       INTEGER NOT NULL REFERENCES recipe (id),
    version         INTEGER NOT NULL CHECK (version >= 1),
    author          TEXT NOT NULL,
    created_at      TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
    note            TEXT NOT NULL DEFAULT '',
    recipe_json     TEXT NOT NULL CHECK (json_valid(recipe_json)),
    checksum_sha256 TEXT NOT NULL CHECK (length(checksum_sha256) = 64),
    substrate_kind  TEXT NOT NULL,
    UNIQUE (recipe_id, version)
);
-- Layers (top first) and their components, linking the ingredients a version
-- uses. The link is by kind and name at save time; NULL when the recipe
-- carries an ingredient the database does not hold (its data are in recipe_json).
CREATE TABLE recipe_layer (
    id                   INTEGER PRIMARY KEY,
    recipe_version_id    INTEGER NOT NULL REFERENCES recipe_version (id),
    position             INTEGER NOT NULL CHECK (position >= 0),
    name                 TEXT NOT NULL,
    thickness_um         REAL NOT NULL,
    binder_name          TEXT NOT NULL,
    binder_ingredient_id INTEGER REFERENCES ingredient (id),
    UNIQUE (recipe_version_id, position)
);
CREATE TABLE recipe_component (
    id              INTEGER PRIMARY KEY,
    recipe_layer_id INTEGER NOT NULL REFERENCES recipe_layer (id),
    position        INTEGER NOT NULL CHECK (position >= 0),
    kind            TEXT NOT NULL,
    name            TEXT NOT NULL,
    volume_fraction REAL NOT NULL,
    ingredient_id   INTEGER REFERENCES ingredient (id),
    UNIQUE (recipe_layer_id, position)
);
CREATE INDEX recipe_layer_by_binder ON recipe_layer (binder_ingredient_id);
CREATE INDEX recipe_component_by_ingredient ON recipe_component (ingredient_id);

CREATE TRIGGER recipe_no_update BEFORE UPDATE ON recipe
BEGIN SELECT RAISE(ABORT, 'recipes are immutable: a saved recipe is never renamed'); END;
CREATE TRIGGER recipe_no_delete BEFORE DELETE ON recipe
BEGIN SELECT RAISE(ABORT, 'recipes are immutable: a saved recipe is never deleted'); END;
CREATE TRIGGER recipe_version_no_update BEFORE UPDATE ON recipe_version
BEGIN SELECT RAISE(ABORT, 'recipe versions are immutable: save a new version instead'); END;
CREATE TRIGGER recipe_version_no_delete BEFORE DELETE ON recipe_version
BEGIN SELECT RAISE(ABORT, 'recipe versions are immutable: a saved version is never deleted'); END;
CREATE TRIGGER recipe_layer_no_update BEFORE UPDATE ON recipe_layer
BEGIN SELECT RAISE(ABORT, 'recipe versions are immutable: their layers cannot change'); END;
CREATE TRIGGER recipe_layer_no_delete BEFORE DELETE ON recipe_layer
BEGIN SELECT RAISE(ABORT, 'recipe versions are immutable: their layers cannot be deleted'); END;
CREATE TRIGGER recipe_component_no_update BEFORE UPDATE ON recipe_component
BEGIN SELECT RAISE(ABORT, 'recipe versions are immutable: their components cannot change'); END;
CREATE TRIGGER recipe_component_no_delete BEFORE DELETE ON recipe_component
BEGIN SELECT RAISE(ABORT, 'recipe versions are immutable: their components cannot be deleted'); END;

-- Measurements of real panels: a BRDF (goniophotometer) or multi-angle
-- spectrophotometer data set, kept as JSON with the geometry it was taken in.
CREATE TABLE measurement (
    id          INTEGER PRIMARY KEY,
    name        TEXT NOT NULL CHECK (length(name) > 0),
    kind        TEXT NOT NULL CHECK (kind IN ('brdf', 'multiangle')),
    instrument  TEXT NOT NULL DEFAULT '',
    geometry    TEXT NOT NULL DEFAULT '',      -- e.g. '45as-15,15,25,45,75,110' or a gonio description
    sample      TEXT NOT NULL DEFAULT '',      -- the panel that was measured
    measured_at TEXT NOT NULL DEFAULT '',
    data_json   TEXT NOT NULL CHECK (json_valid(data_json)),
    source      TEXT NOT NULL DEFAULT '',
    created_at  TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);

-- A fit of a recipe version to a measurement and how well it matched.
CREATE TABLE fit (
    id                INTEGER PRIMARY KEY,
    recipe_version_id INTEGER NOT NULL REFERENCES recipe_version (id),
    measurement_id    INTEGER NOT NULL REFERENCES measurement (id),
    method            TEXT NOT NULL DEFAULT '',
    residual_rms      REAL CHECK (residual_rms IS NULL OR residual_rms >= 0),
    residuals_json    TEXT NOT NULL DEFAULT '[]' CHECK (json_valid(residuals_json)),
    parameters_json   TEXT NOT NULL DEFAULT '{}' CHECK (json_valid(parameters_json)),
    note              TEXT NOT NULL DEFAULT '',
    created_at        TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))
);
CREATE INDEX fit_by_version ON fit (recipe_version_id);
CREATE INDEX fit_by_measurement ON fit (measurement_id);
