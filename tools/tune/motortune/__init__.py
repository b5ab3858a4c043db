"""motortune: a motor's data sheet (TOML) to a motor profile header, and a profile back in
engineering units, with the core's own arithmetic and checks read through a C probe."""
