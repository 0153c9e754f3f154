//! A render's parameters, declared once (`render::params::PARAMS`): every door
//! reads them from the declaration, and a configuration written back by
//! the command that renders it again reads back the same.

use umbra::sim::render::{RenderError, RenderRequest};

use umbra::sim::render::params::Kind;

use umbra::sim::render::params::ParamError;

use umbra::sim::render::params::RenderParam;
use umbra::sim::{Algorithm, Culling, Limits, RenderConfig, Scene};

/// The defaults, worked by hand from the papers' set-up the README names:
/// second depth with virtual samples, 24-bit 1024² map, bilinear, no bias,
/// 4² reference rays, the scene's image.
#[test]
fn the_default_request_is_the_default_render_at_the_scenes_image() {
    let cfg = RenderRequest::DEFAULT.config([320, 180]).expect("the default algorithm");
    assert_eq!(cfg, RenderConfig { width: 320, height: 180, ..RenderConfig::DEFAULT });
    assert_eq!(cfg.algorithm, Algorithm::Second);
    assert_eq!((cfg.map_size, cfg.reference_rays, cfg.bias), (1024, 4, 0.0));
    assert!(cfg.virtual_samples);
}

/// The command that renders a configuration again, read back parameter by
/// parameter, is the configuration: every parameter's writer and reader
/// agree, the algorithm's own parameter included.
#[test]
fn the_render_again_command_reads_back_as_the_configuration() {
    let d = RenderConfig::DEFAULT;
    let configs = [
        d,
        RenderConfig { algorithm: Algorithm::Dual { offset: 0.03 }, map_size: 512, ..d },
        RenderConfig { algorithm: Algorithm::BiasRange { hi: 0.02 }, bias: 0.001, ..d },
        RenderConfig { virtual_samples: false, culling: Culling::OFF, reference_rays: 16, ..d },
        RenderConfig { filter: "jitter8,res-factor=1.5".parse().expect("a filter"), width: 7, height: 9, ..d },
    ];
    let crowd = umbra::sim::Scene::bundled("crowd").expect("bundled");
    for cfg in configs {
        let command = cfg.command(&crowd);
        let words: Vec<&str> = command.split_whitespace().collect();
        assert_eq!(&words[..3], ["umbra", "render", "crowd"], "{command}");
        let mut request = RenderRequest::DEFAULT;
        let mut k = 3;
        while k < words.len() {
            let p = RenderParam::named(words[k]).expect("a parameter's flag");
            if p.kind == Kind::Flag {
                request.set(p.name, "false").expect("a switch");
                k += 1;
            } else {
                request.set(words[k], words[k + 1]).expect("a value the command wrote");
                k += 2;
            }
        }
        assert_eq!(request.config([1, 1]).expect("an algorithm"), cfg, "{command}");
    }
}

/// A value out of range or of the wrong kind is refused with the
/// parameter's name, by its declaration, before any render.
#[test]
fn a_bad_value_names_the_parameter() {
    let mut r = RenderRequest::DEFAULT;
    for (name, value) in [("bias", "1.5"), ("map", "0"), ("reference-rays", "17"), ("algo", "third"), ("depth", "d8")] {
        let e = r.set(name, value).expect_err("refused");
        assert!(matches!(&e, ParamError::Value { value: v, .. } if v == value), "{e}");
        assert!(e.to_string().contains(value), "{e}");
    }
    assert!(matches!(r.set("colour", "red"), Err(ParamError::Unknown(_))));
    // Aliases: the old flags and Python's old keywords.
    for (alias, name) in [("rays", "reference_rays"), ("culling", "cull"), ("format", "depth"), ("size", "map")] {
        assert_eq!(RenderParam::named(alias).expect("an alias").name, name);
    }
    // The request, untouched by what it refused, is still the default.
    assert_eq!(r, RenderRequest::DEFAULT);
}

/// The check happens once, in `RenderConfig::check`, and covers the
/// limits: a map beyond them is refused before any render.
#[test]
fn the_one_check_covers_values_and_limits() {
    let scene = Scene::open("weiskopf-l", &Limits::DEFAULT).expect("bundled");
    let small = Limits { max_map_side: 256, ..Limits::DEFAULT };
    let over = RenderConfig { map_size: 512, ..RenderConfig::DEFAULT };
    assert!(matches!(over.check(&scene, &small), Err(RenderError::Limit(_))));
    let bad = RenderConfig { bias: -0.5, ..RenderConfig::DEFAULT };
    assert!(matches!(bad.check(&scene, &Limits::DEFAULT), Err(RenderError::Config(_))));
    let job = RenderConfig { map_size: 256, ..RenderConfig::DEFAULT }.check(&scene, &small).expect("within");
    assert_eq!(job.config().map_size, 256);
    assert_eq!(job.scene().name, scene.name);
}
