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
        name: "crossing",
        text: include_str!("../../scenes/crossing.toml"),
    },
];

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
