//! Scenes shipped with the binary (the files in `scenes/`, embedded at compile time).

/// A built-in scene.
pub struct Builtin {
    pub name: &'static str,
    pub text: &'static str,
}

pub const BUILTINS: &[Builtin] = &[
    Builtin {
        name: "strip-channel",
        text: include_str!("../../scenes/strip-channel.toml"),
    },
    Builtin {
        name: "cantilever",
        text: include_str!("../../scenes/cantilever.toml"),
    },
    Builtin {
        name: "block-slide",
        text: include_str!("../../scenes/block-slide.toml"),
    },
    Builtin {
        name: "hertz",
        text: include_str!("../../scenes/hertz.toml"),
    },
    Builtin {
        name: "hertz-axisym",
        text: include_str!("../../scenes/hertz-axisym.toml"),
    },
    Builtin {
        name: "crossing",
        text: include_str!("../../scenes/crossing.toml"),
    },
    Builtin {
        name: "half-disc",
        text: include_str!("../../scenes/half-disc.toml"),
    },
    Builtin {
        name: "contact-patch",
        text: include_str!("../../scenes/contact-patch.toml"),
    },
    Builtin {
        name: "ironing",
        text: include_str!("../../scenes/ironing.toml"),
    },
    Builtin {
        name: "flat-punch",
        text: include_str!("../../scenes/flat-punch.toml"),
    },
    Builtin {
        name: "capstan",
        text: include_str!("../../scenes/capstan.toml"),
    },
    Builtin {
        name: "capstan-polygon",
        text: include_str!("../../scenes/capstan-polygon.toml"),
    },
    Builtin {
        name: "concentric-spheres",
        text: include_str!("../../scenes/concentric-spheres.toml"),
    },
    Builtin {
        name: "cantilever-3d",
        text: include_str!("../../scenes/cantilever-3d.toml"),
    },
    Builtin {
        name: "hertz-3d",
        text: include_str!("../../scenes/hertz-3d.toml"),
    },
    Builtin {
        name: "slide-3d",
        text: include_str!("../../scenes/slide-3d.toml"),
    },
    Builtin {
        name: "strip-channel-3d",
        text: include_str!("../../scenes/strip-channel-3d.toml"),
    },
    Builtin {
        name: "twisting-hemisphere",
        text: include_str!("../../scenes/twisting-hemisphere.toml"),
    },
];

/// Files the built-in scenes refer to (meshes), by the name they use.
pub const FILES: &[(&str, &[u8])] = &[("half-disc.msh", include_bytes!("../../scenes/half-disc.msh"))];

/// A file shipped with the built-in scenes (`mesh = { kind = "gmsh", file = NAME }`).
pub fn file(name: &str) -> Option<&'static [u8]> {
    FILES.iter().find(|f| f.0 == name).map(|f| f.1)
}

/// The built-in scene called `name`.
pub fn find(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

/// The `description` line of a built-in (for `contrail scenes`).
pub fn description(b: &Builtin) -> String {
    toml::from_str::<toml::Table>(b.text)
        .ok()
        .and_then(|t| t.get("description").and_then(|d| d.as_str()).map(str::to_string))
        .unwrap_or_default()
}
