//! The limit options (`--max-*`): what the simulator accepts, given
//! before or after the subcommand (`umbra --max-image-pixels 1000000
//! study …` or `umbra study --max-image-pixels …`). They are listed once,
//! in `umbra --help`'s Limits section; each subcommand's help says where
//! instead of repeating them ([`listed_once`]).

use clap::{Args, Command};
use umbra_sim::cost::arch::Unit;
use umbra_sim::input::limits::Limits;

/// What a subcommand's help says in place of the limits.
const WHERE: &str = "Limits on input (--max-*): see `umbra --help`; they may be given before or after the command.";

/// What the simulator accepts, each checked before anything of that size is
/// allocated (`umbra_sim::input::limits`). Options, not scene-file keys: a file
/// cannot raise the limits it is read under.
#[derive(clap::Args, Debug, Clone, Copy)]
#[command(next_help_heading = "Limits")]
pub(super) struct LimitArgs {
    /// Largest light-map side, texels (a dual 24-bit map of side s takes 8·s² bytes).
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_map_side)]
    max_map_side: u32,
    /// Largest camera image side, pixels.
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_image_side)]
    max_image_side: u32,
    /// Most camera image pixels (a render keeps up to 160 bytes a pixel).
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_image_pixels)]
    max_image_pixels: u64,
    /// Most triangles of a scene, every object together (a render keeps up to 1024 bytes a triangle), at most 2^28.
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_triangles, value_parser = clap::value_parser!(u64).range(1..=1 << 28))]
    max_triangles: u64,
    /// Largest file read (an OBJ mesh, a `--matrix` file, study results to merge), bytes.
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_file_bytes)]
    max_file_bytes: u64,
    /// Largest TOML file read (a scene, a sweep, an architecture), bytes (its parse keeps about 96 bytes a byte).
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_text_bytes)]
    max_text_bytes: u64,
    /// Most objects of a scene file.
    #[arg(long, global = true, default_value_t = Limits::DEFAULT.max_objects)]
    max_objects: u64,
    /// Most memory a run may take, bytes or with a unit (16GiB): a render, a study's scenes, reference and renders at once, a TOML file's parse, each bounded before it starts [default: 3/4 of this machine's physical memory; 16GiB where the system does not say]
    #[arg(long, global = true, value_parser = memory)]
    max_memory: Option<u64>,
}

/// A `--max-memory` value: bytes, or a size as architecture files write
/// one (`16GiB`, `512MB`, `1TiB`: the one reader of sizes, [`Unit::Bytes`]).
fn memory(text: &str) -> Result<u64, String> {
    let bytes = match text.trim().parse::<f64>() {
        Ok(plain) => plain,
        Err(_) => Unit::Bytes.parse(text).map_err(|e| e.to_string())?,
    };
    if !(bytes >= 1.0 && bytes < 2f64.powi(63)) {
        return Err(format!("`{text}` is not a size from 1 B to 8 EiB"));
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss, reason = "checked in range")]
    Ok(bytes as u64)
}

impl LimitArgs {
    /// The limits the options give.
    pub(super) fn limits(self) -> Limits {
        Limits {
            max_map_side: self.max_map_side,
            max_image_side: self.max_image_side,
            max_image_pixels: self.max_image_pixels,
            max_triangles: self.max_triangles,
            max_file_bytes: self.max_file_bytes,
            max_text_bytes: self.max_text_bytes,
            max_objects: self.max_objects,
            max_memory: self.max_memory.unwrap_or_else(|| Limits::for_machine().max_memory),
        }
    }
}

/// `umbra`'s command with every subcommand's help (at every depth) saying
/// where the limits are listed instead of listing them: each subcommand
/// holds its own hidden copy of each limit option, which clap then does
/// not copy from `umbra` (as it does a global option), and reads it there.
pub(super) fn listed_once(umbra: Command) -> Command {
    let limits = LimitArgs::augment_args(Command::new("limits"));
    let hidden: Vec<clap::Arg> = limits.get_arguments().map(|a| a.clone().hide(true)).collect();
    hidden_below(umbra, &hidden)
}

/// `command` with the options `hidden` in its subcommands and theirs.
fn hidden_below(command: Command, hidden: &[clap::Arg]) -> Command {
    let names: Vec<String> = command.get_subcommands().map(|s| s.get_name().to_owned()).collect();
    names.into_iter().fold(command, |command, name| {
        command.mut_subcommand(name, |sub| {
            let sub = hidden.iter().fold(sub, |sub, a| sub.arg(a.clone())).after_help(WHERE);
            hidden_below(sub, hidden)
        })
    })
}
