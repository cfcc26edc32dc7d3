//! Expressions compiled to a flat register program. Every instruction writes a new slot
//! (SSA), identical subexpressions are shared across all outputs (hash-consing), and
//! parameters and constants are folded at compile time, so a problem's right-hand side costs
//! about what the same formulas written by hand cost.

use std::cell::RefCell;
use std::collections::HashMap;

use super::parse::{Fn1, Fn2, Node};

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Instr {
    Const(f64),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    Neg(u32),
    Pow(u32, u32),
    PowI(u32, i32),
    Atan2(u32, u32),
    Min(u32, u32),
    Max(u32, u32),
    Sin(u32),
    Cos(u32),
    Tan(u32),
    Exp(u32),
    Ln(u32),
    Sqrt(u32),
    Abs(u32),
    /// sign of a (−1, 0, 1): the derivative of |a|
    Sign(u32),
    /// `if a ≤ b { x } else { y }`: the derivatives of min and max
    PickLe(u32, u32, u32, u32),
}

impl Instr {
    /// A hashable identity: equal keys compute equal values (hash-consing).
    fn key(&self) -> (u8, u64, u64, u64, u64) {
        use Instr::*;
        let u = |s: u32| s as u64;
        match *self {
            Const(c) => (0, c.to_bits(), 0, 0, 0),
            Add(a, b) => (1, u(a), u(b), 0, 0),
            Sub(a, b) => (2, u(a), u(b), 0, 0),
            Mul(a, b) => (3, u(a), u(b), 0, 0),
            Div(a, b) => (4, u(a), u(b), 0, 0),
            Neg(a) => (5, u(a), 0, 0, 0),
            Pow(a, b) => (6, u(a), u(b), 0, 0),
            PowI(a, e) => (7, u(a), e as i64 as u64, 0, 0),
            Atan2(a, b) => (8, u(a), u(b), 0, 0),
            Min(a, b) => (9, u(a), u(b), 0, 0),
            Max(a, b) => (10, u(a), u(b), 0, 0),
            Sin(a) => (11, u(a), 0, 0, 0),
            Cos(a) => (12, u(a), 0, 0, 0),
            Tan(a) => (13, u(a), 0, 0, 0),
            Exp(a) => (14, u(a), 0, 0, 0),
            Ln(a) => (15, u(a), 0, 0, 0),
            Sqrt(a) => (16, u(a), 0, 0, 0),
            Abs(a) => (17, u(a), 0, 0, 0),
            Sign(a) => (18, u(a), 0, 0, 0),
            PickLe(a, b, x, y) => (19, u(a), u(b), u(x), u(y)),
        }
    }

    /// The slots this instruction reads.
    pub(super) fn operands(&self) -> ([u32; 4], usize) {
        use Instr::*;
        match *self {
            Const(_) => ([0; 4], 0),
            Neg(a)
            | PowI(a, _)
            | Sin(a)
            | Cos(a)
            | Tan(a)
            | Exp(a)
            | Ln(a)
            | Sqrt(a)
            | Abs(a)
            | Sign(a) => ([a, 0, 0, 0], 1),
            Add(a, b)
            | Sub(a, b)
            | Mul(a, b)
            | Div(a, b)
            | Pow(a, b)
            | Atan2(a, b)
            | Min(a, b)
            | Max(a, b) => ([a, b, 0, 0], 2),
            PickLe(a, b, x, y) => ([a, b, x, y], 4),
        }
    }

    /// The same instruction reading `map(slot)` for each operand.
    pub(super) fn remap(&self, map: impl Fn(u32) -> u32) -> Instr {
        use Instr::*;
        match *self {
            Const(c) => Const(c),
            Add(a, b) => Add(map(a), map(b)),
            Sub(a, b) => Sub(map(a), map(b)),
            Mul(a, b) => Mul(map(a), map(b)),
            Div(a, b) => Div(map(a), map(b)),
            Neg(a) => Neg(map(a)),
            Pow(a, b) => Pow(map(a), map(b)),
            PowI(a, e) => PowI(map(a), e),
            Atan2(a, b) => Atan2(map(a), map(b)),
            Min(a, b) => Min(map(a), map(b)),
            Max(a, b) => Max(map(a), map(b)),
            Sin(a) => Sin(map(a)),
            Cos(a) => Cos(map(a)),
            Tan(a) => Tan(map(a)),
            Exp(a) => Exp(map(a)),
            Ln(a) => Ln(map(a)),
            Sqrt(a) => Sqrt(map(a)),
            Abs(a) => Abs(map(a)),
            Sign(a) => Sign(map(a)),
            PickLe(a, b, x, y) => PickLe(map(a), map(b), map(x), map(y)),
        }
    }
}

/// A compiled set of expressions over the inputs `[t, x_0, …, x_{n−1}]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    pub(super) n_inputs: usize,
    pub(super) code: Vec<Instr>,
    /// slot of each output
    pub(super) outputs: Vec<u32>,
}

/// Applies a one-argument function exactly as the evaluator does (used for folding too).
fn apply1(f: Fn1, a: f64) -> f64 {
    match f {
        Fn1::Neg => -a,
        Fn1::Sin => a.sin(),
        Fn1::Cos => a.cos(),
        Fn1::Tan => a.tan(),
        Fn1::Exp => a.exp(),
        Fn1::Ln => a.ln(),
        Fn1::Sqrt => a.sqrt(),
        Fn1::Abs => a.abs(),
    }
}

fn apply2(f: Fn2, a: f64, b: f64) -> f64 {
    match f {
        Fn2::Add => a + b,
        Fn2::Sub => a - b,
        Fn2::Mul => a * b,
        Fn2::Div => a / b,
        Fn2::Pow => a.powf(b),
        Fn2::Atan2 => a.atan2(b),
        Fn2::Min => a.min(b),
        Fn2::Max => a.max(b),
    }
}

pub(super) struct Builder {
    pub n_inputs: usize,
    pub code: Vec<Instr>,
    seen: HashMap<(u8, u64, u64, u64, u64), u32>,
}

/// A value while building: a number known at compile time, or a slot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Val {
    Num(f64),
    Slot(u32),
}

impl Builder {
    pub fn new(n_inputs: usize) -> Self {
        Self {
            n_inputs,
            code: Vec::new(),
            seen: HashMap::new(),
        }
    }

    /// The slot of `instr`, shared with an identical earlier one.
    pub fn emit(&mut self, instr: Instr) -> u32 {
        let key = instr.key();
        if let Some(&s) = self.seen.get(&key) {
            return s;
        }
        let slot = (self.n_inputs + self.code.len()) as u32;
        self.code.push(instr);
        self.seen.insert(key, slot);
        slot
    }

    pub fn slot(&mut self, v: Val) -> u32 {
        match v {
            Val::Slot(s) => s,
            Val::Num(c) => self.emit(Instr::Const(c)),
        }
    }

    pub fn node(&mut self, node: &Node) -> Val {
        match node {
            Node::Num(v) => Val::Num(*v),
            Node::Input(i) => Val::Slot(*i as u32),
            Node::Call1(f, a) => match self.node(a) {
                Val::Num(c) => Val::Num(apply1(*f, c)),
                Val::Slot(s) => {
                    let instr = match f {
                        Fn1::Neg => Instr::Neg(s),
                        Fn1::Sin => Instr::Sin(s),
                        Fn1::Cos => Instr::Cos(s),
                        Fn1::Tan => Instr::Tan(s),
                        Fn1::Exp => Instr::Exp(s),
                        Fn1::Ln => Instr::Ln(s),
                        Fn1::Sqrt => Instr::Sqrt(s),
                        Fn1::Abs => Instr::Abs(s),
                    };
                    Val::Slot(self.emit(instr))
                }
            },
            Node::Call2(f, a, b) => {
                let (a, b) = (self.node(a), self.node(b));
                if let (Val::Num(x), Val::Num(y)) = (&a, &b) {
                    return Val::Num(apply2(*f, *x, *y));
                }
                // small whole powers by multiplication: x^2 is exactly x*x
                if let (Fn2::Pow, Val::Slot(s), Val::Num(e)) = (f, &a, &b)
                    && e.fract() == 0.0
                    && e.abs() <= 64.0
                {
                    let e = *e as i32;
                    return Val::Slot(match e {
                        1 => *s,
                        2 => self.emit(Instr::Mul(*s, *s)),
                        _ => self.emit(Instr::PowI(*s, e)),
                    });
                }
                let (a, b) = (self.slot(a), self.slot(b));
                let instr = match f {
                    Fn2::Add => Instr::Add(a, b),
                    Fn2::Sub => Instr::Sub(a, b),
                    Fn2::Mul => Instr::Mul(a, b),
                    Fn2::Div => Instr::Div(a, b),
                    Fn2::Pow => Instr::Pow(a, b),
                    Fn2::Atan2 => Instr::Atan2(a, b),
                    Fn2::Min => Instr::Min(a, b),
                    Fn2::Max => Instr::Max(a, b),
                };
                Val::Slot(self.emit(instr))
            }
        }
    }
}

thread_local! {
    // registers for evaluation through `&self` (System::rhs); grown once per thread
    static REGS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

impl Program {
    /// Compiles expressions over `n_inputs` inputs (`Node::Input(i)`, i < n_inputs).
    pub fn compile(n_inputs: usize, exprs: &[Node]) -> Self {
        let mut b = Builder::new(n_inputs);
        let outputs = exprs
            .iter()
            .map(|e| {
                let v = b.node(e);
                b.slot(v)
            })
            .collect();
        Program {
            n_inputs,
            code: b.code,
            outputs,
        }
    }

    /// The program computing `outputs` from `code`, keeping only the instructions they need.
    pub(super) fn pruned(n_inputs: usize, code: Vec<Instr>, outputs: Vec<u32>) -> Self {
        let mut live = vec![false; n_inputs + code.len()];
        for &o in &outputs {
            live[o as usize] = true;
        }
        for k in (0..code.len()).rev() {
            if live[n_inputs + k] {
                let (ops, m) = code[k].operands();
                for &s in &ops[..m] {
                    live[s as usize] = true;
                }
            }
        }
        let mut new_slot: Vec<u32> = (0..n_inputs as u32).collect();
        new_slot.resize(n_inputs + code.len(), 0);
        let mut kept = Vec::new();
        for (k, ins) in code.iter().enumerate() {
            if live[n_inputs + k] {
                new_slot[n_inputs + k] = (n_inputs + kept.len()) as u32;
                kept.push(ins.remap(|s| new_slot[s as usize]));
            }
        }
        Program {
            n_inputs,
            code: kept,
            outputs: outputs.iter().map(|&o| new_slot[o as usize]).collect(),
        }
    }

    /// Whether every output is the constant zero (e.g. ∂f/∂t of an autonomous system).
    pub fn is_zero(&self) -> bool {
        self.outputs.iter().all(|&o| {
            (o as usize) >= self.n_inputs
                && self.code[o as usize - self.n_inputs] == Instr::Const(0.0)
        })
    }

    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Number of instructions (after sharing and folding).
    pub fn len(&self) -> usize {
        self.code.len()
    }

    pub fn is_empty(&self) -> bool {
        self.code.is_empty()
    }

    /// Evaluates at time t and state x (inputs `[t, x…]`) into `out`, using `regs` as
    /// scratch (grown if needed, so reuse it).
    pub fn eval_with(&self, t: f64, x: &[f64], out: &mut [f64], regs: &mut Vec<f64>) {
        debug_assert_eq!(x.len() + 1, self.n_inputs);
        let total = self.n_inputs + self.code.len();
        if regs.len() < total {
            regs.resize(total, 0.0);
        }
        let r = &mut regs[..total];
        r[0] = t;
        r[1..self.n_inputs].copy_from_slice(x);
        for (k, ins) in self.code.iter().enumerate() {
            let i = self.n_inputs + k;
            // operands always precede the slot being written
            let g = |s: u32| r[s as usize];
            let v = match *ins {
                Instr::Const(c) => c,
                Instr::Add(a, b) => g(a) + g(b),
                Instr::Sub(a, b) => g(a) - g(b),
                Instr::Mul(a, b) => g(a) * g(b),
                Instr::Div(a, b) => g(a) / g(b),
                Instr::Neg(a) => -g(a),
                Instr::Pow(a, b) => g(a).powf(g(b)),
                Instr::PowI(a, e) => g(a).powi(e),
                Instr::Atan2(a, b) => g(a).atan2(g(b)),
                Instr::Min(a, b) => g(a).min(g(b)),
                Instr::Max(a, b) => g(a).max(g(b)),
                Instr::Sin(a) => g(a).sin(),
                Instr::Cos(a) => g(a).cos(),
                Instr::Tan(a) => g(a).tan(),
                Instr::Exp(a) => g(a).exp(),
                Instr::Ln(a) => g(a).ln(),
                Instr::Sqrt(a) => g(a).sqrt(),
                Instr::Abs(a) => g(a).abs(),
                Instr::Sign(a) => {
                    let v = g(a);
                    if v > 0.0 {
                        1.0
                    } else if v < 0.0 {
                        -1.0
                    } else {
                        v
                    }
                }
                Instr::PickLe(a, b, x, y) => {
                    if g(a) <= g(b) {
                        g(x)
                    } else {
                        g(y)
                    }
                }
            };
            r[i] = v;
        }
        for (o, &s) in out.iter_mut().zip(&self.outputs) {
            *o = r[s as usize];
        }
    }

    /// [`Program::eval_with`] on this thread's scratch registers (no allocation after the
    /// first call).
    pub fn eval(&self, t: f64, x: &[f64], out: &mut [f64]) {
        REGS.with(|regs| self.eval_with(t, x, out, &mut regs.borrow_mut()))
    }
}
