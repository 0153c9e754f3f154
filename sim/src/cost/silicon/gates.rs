//! Gate-equivalent counts of the datapaths' building blocks, per bit:
//! what logic synthesis makes of small width-parameterised blocks.
//!
//! Each coefficient is yosys 0.23's count (`synth -flatten; abc -g
//! AND,NAND,OR,NOR,XOR,XNOR,MUX`) of a block written in Verilog at widths
//! 8 to 32 (multipliers 8×8 to 16×16), its cells weighed in NAND2
//! equivalents by their areas in the Nangate 45 nm Open Cell Library
//! (NAND2_X1 0.798 µm²: NOT 0.667, NAND/NOR 1, AND/OR 1.333, XOR/XNOR 2,
//! MUX2 2.333, D flip-flop 5.667), fitted to every width within 15 %.
//! `synthesis::gate_counts_match_yosys` (run where yosys is installed)
//! synthesises the blocks again and holds each coefficient to them.
//!
//! ```
//! use umbra_sim::cost::silicon::gates::{Block, gate_equivalents};
//! // A 16-bit comparator: 16 bits at 7 NAND2 equivalents each.
//! assert_eq!(gate_equivalents(Block::Compare, 16, 1), 112.0);
//! ```

/// A building block of a datapath.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Block {
    /// A ripple or prefix adder `a + b` (an incrementer, a forward
    /// difference, a bias).
    Add,
    /// An unsigned magnitude comparator `a < b` (a depth test).
    Compare,
    /// An unsigned multiplier of a `w`-bit by a `v`-bit operand.
    Multiply,
    /// A register of flip-flops.
    Register,
    /// A two-way multiplexer.
    Mux,
}

impl Block {
    /// Every block, in the order the synthesis check takes them.
    pub const ALL: [Self; 5] = [Self::Add, Self::Compare, Self::Multiply, Self::Register, Self::Mux];

    /// NAND2 equivalents per bit (per bit of each operand for a
    /// multiplier: per `w·v`).
    #[must_use]
    pub const fn per_bit(self) -> f64 {
        match self {
            Self::Add => 6.9,
            Self::Compare => 7.0,
            Self::Multiply => 7.7,
            Self::Register => 17.0 / 3.0,
            Self::Mux => 7.0 / 3.0,
        }
    }

    /// Its name in the synthesis check's Verilog.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Add => "add",
            Self::Compare => "cmp",
            Self::Multiply => "mul",
            Self::Register => "regw",
            Self::Mux => "mux",
        }
    }
}

/// NAND2 equivalents of `block` at width `w` (and `v`, a multiplier's
/// second operand; 1 otherwise).
#[must_use]
pub fn gate_equivalents(block: Block, w: u32, v: u32) -> f64 {
    let bits = if block == Block::Multiply { f64::from(w) * f64::from(v) } else { f64::from(w) };
    block.per_bit() * bits
}

#[cfg(test)]
mod synthesis {
    //! The coefficients against yosys itself: each block written in
    //! Verilog, synthesised at several widths, its cells weighed as the
    //! module says. Needs `yosys` on the path (`.ci/run` installs it).

    use super::{Block, gate_equivalents};
    use std::process::Command;

    /// Each block's Verilog, width-parameterised.
    fn verilog(b: Block) -> &'static str {
        match b {
            Block::Add => {
                "module add #(parameter W=8)(input [W-1:0] a, input [W-1:0] b, output [W:0] y); assign y = a + b; endmodule"
            }
            Block::Compare => {
                "module cmp #(parameter W=8)(input [W-1:0] a, input [W-1:0] b, output y); assign y = a < b; endmodule"
            }
            Block::Multiply => {
                "module mul #(parameter W=8, parameter V=8)(input [W-1:0] a, input [V-1:0] b, output [W+V-1:0] y); assign y = a * b; endmodule"
            }
            Block::Register => {
                "module regw #(parameter W=8)(input clk, input [W-1:0] d, output reg [W-1:0] q); always @(posedge clk) q <= d; endmodule"
            }
            Block::Mux => {
                "module mux #(parameter W=8)(input s, input [W-1:0] a, input [W-1:0] b, output [W-1:0] y); assign y = s ? a : b; endmodule"
            }
        }
    }

    /// A cell's NAND2 equivalents (Nangate 45 nm areas over NAND2_X1's).
    fn weight(cell: &str) -> f64 {
        match cell {
            "$_NOT_" => 2.0 / 3.0,
            "$_NAND_" | "$_NOR_" => 1.0,
            "$_AND_" | "$_OR_" | "$_ANDNOT_" | "$_ORNOT_" => 4.0 / 3.0,
            "$_XOR_" | "$_XNOR_" => 2.0,
            "$_MUX_" => 7.0 / 3.0,
            c if c.starts_with("$_DFF") => 17.0 / 3.0,
            c => panic!("no weight for cell {c}"),
        }
    }

    /// yosys's NAND2 equivalents of `b` at `w` (and `v`).
    fn synthesised(dir: &std::path::Path, b: Block, w: u32, v: u32) -> f64 {
        let src = dir.join(format!("{}.v", b.name()));
        std::fs::write(&src, verilog(b)).expect("write the Verilog");
        let stat = dir.join("stat.json");
        let v_set = if b == Block::Multiply { format!(" -set V {v}") } else { String::new() };
        let script = format!(
            "read_verilog {}; chparam -set W {w}{v_set} {top}; synth -top {top} -flatten; abc -g AND,NAND,OR,NOR,XOR,XNOR,MUX; opt_clean; tee -q -o {} stat -json",
            src.display(),
            stat.display(),
            top = b.name()
        );
        let out = Command::new("yosys").args(["-q", "-p", &script]).output().expect("run yosys");
        assert!(out.status.success(), "yosys: {}", String::from_utf8_lossy(&out.stderr));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&stat).expect("stat")).expect("stat JSON");
        let cells = json["design"]["num_cells_by_type"].as_object().expect("cells by type");
        cells.iter().map(|(c, n)| weight(c) * n.as_f64().expect("a count")).sum()
    }

    /// A scratch folder, removed however the test ends.
    struct Scratch(std::path::PathBuf);

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    #[test]
    #[ignore = "needs yosys (apt-get install yosys); .ci/run installs it and runs this"]
    fn gate_counts_match_yosys() {
        let scratch = Scratch(std::env::temp_dir().join(format!("umbra-yosys-{}", std::process::id())));
        let dir = &scratch.0;
        std::fs::create_dir_all(dir).expect("scratch folder");
        let mut worst: f64 = 0.0;
        for b in Block::ALL {
            let widths: &[(u32, u32)] = if b == Block::Multiply {
                &[(8, 8), (12, 12), (16, 16), (16, 8)]
            } else {
                &[(8, 1), (12, 1), (16, 1), (24, 1), (32, 1)]
            };
            for &(w, v) in widths {
                let (model, yosys) = (gate_equivalents(b, w, v), synthesised(dir, b, w, v));
                let off = (model / yosys - 1.0).abs();
                worst = worst.max(off);
                // 15 %: the spread of a per-bit figure over widths 8 to 32
                // (an adder's cells per bit grow from 6.6 to 7.8).
                assert!(off <= 0.15, "{} {w}×{v}: model {model:.1} GE, yosys {yosys:.1} GE", b.name());
            }
        }
        eprintln!("worst: {:.1} %", 100.0 * worst);
    }
}
