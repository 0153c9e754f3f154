//! The bundled architecture files (presets): the machines `--arch` names
//! without a file.

/// The bundled architecture files (presets), by name.
pub const BUNDLED: [(&str, &str); 6] = [
    ("pixelflow", include_str!("../../../../arch/pixelflow.toml")),
    ("talisman", include_str!("../../../../arch/talisman.toml")),
    ("immediate", include_str!("../../../../arch/immediate.toml")),
    ("mobile-tbdr", include_str!("../../../../arch/mobile-tbdr.toml")),
    ("desktop-imr", include_str!("../../../../arch/desktop-imr.toml")),
    ("r300", include_str!("../../../../arch/r300.toml")),
];
