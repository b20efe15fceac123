-- PaintLab database, schema version 2: what production sheets and imported
-- spectra need and version 1 lacked.
--
-- A binder is stored with the density of its dry film (ingredient.density_g_cm3);
-- a production sheet also needs the binder as it is bought: a resin solution
-- or dispersion with a non-volatile (solids) content by mass, and the density
-- of its volatile part to turn the solvent mass into a wet volume. NULL
-- solids means the binder is weighed as 100 % solids (no volatile part).
ALTER TABLE binder ADD COLUMN solids_mass_fraction REAL
    CHECK (solids_mass_fraction IS NULL OR (solids_mass_fraction > 0 AND solids_mass_fraction <= 1));
ALTER TABLE binder ADD COLUMN volatile_density_g_cm3 REAL
    CHECK (volatile_density_g_cm3 IS NULL OR volatile_density_g_cm3 > 0);

-- Spectra imported on their own (a spectrophotometer's CGATS export, a CSV
-- of a measured reflectance) are found again by name; ingredient spectra
-- keep a NULL name (they are reached through their ingredient).
ALTER TABLE spectrum ADD COLUMN name TEXT CHECK (name IS NULL OR length(name) > 0);
CREATE UNIQUE INDEX spectrum_by_name ON spectrum (name) WHERE name IS NOT NULL;
