//! Exact derivatives of a compiled program by symbolic differentiation in forward mode: every
//! instruction's partial derivatives with respect to each input are new instructions of the
//! same program form, built with the same sharing (hash-consing) and constant folding, so the
//! Jacobian of a right-hand side costs about what the hand-written Jacobian would. Zero
//! derivatives are known at compile time and never emitted, so a sparse Jacobian stays cheap.
//!
//! The rules are the textbook ones (d(a/b) = (da − q·db)/b with q = a/b, d(aᵇ) = q·(db·ln a
//! + b·da/a), constant exponents as b·a^(b−1)·da); min, max and |·| take the derivative of the
//! branch they pick (at a tie, the first argument's).

use super::program::{Builder, Instr, Program, Val};

/// Algebra on values that folds numbers and drops zeros and ones.
struct Alg<'a> {
    b: &'a mut Builder,
}

impl Alg<'_> {
    fn op(&mut self, instr: Instr) -> Val {
        Val::Slot(self.b.emit(instr))
    }

    fn s(&mut self, v: Val) -> u32 {
        self.b.slot(v)
    }

    fn add(&mut self, x: Val, y: Val) -> Val {
        match (x, y) {
            (Val::Num(a), Val::Num(b)) => Val::Num(a + b),
            (Val::Num(z), v) | (v, Val::Num(z)) if z == 0.0 => v,
            _ => {
                let (a, b) = (self.s(x), self.s(y));
                self.op(Instr::Add(a, b))
            }
        }
    }

    fn sub(&mut self, x: Val, y: Val) -> Val {
        match (x, y) {
            (Val::Num(a), Val::Num(b)) => Val::Num(a - b),
            (v, Val::Num(z)) if z == 0.0 => v,
            (Val::Num(z), v) if z == 0.0 => self.neg(v),
            _ => {
                let (a, b) = (self.s(x), self.s(y));
                self.op(Instr::Sub(a, b))
            }
        }
    }

    fn mul(&mut self, x: Val, y: Val) -> Val {
        match (x, y) {
            (Val::Num(a), Val::Num(b)) => Val::Num(a * b),
            // 0·y = 0 even where y is not finite: the zero is structural (∂x_j/∂x_k, k ≠ j)
            (Val::Num(z), _) | (_, Val::Num(z)) if z == 0.0 => Val::Num(0.0),
            (Val::Num(o), v) | (v, Val::Num(o)) if o == 1.0 => v,
            (Val::Num(m), v) | (v, Val::Num(m)) if m == -1.0 => self.neg(v),
            _ => {
                let (a, b) = (self.s(x), self.s(y));
                self.op(Instr::Mul(a, b))
            }
        }
    }

    fn div(&mut self, x: Val, y: Val) -> Val {
        match (x, y) {
            (Val::Num(a), Val::Num(b)) => Val::Num(a / b),
            (Val::Num(z), _) if z == 0.0 => Val::Num(0.0),
            (v, Val::Num(o)) if o == 1.0 => v,
            _ => {
                let (a, b) = (self.s(x), self.s(y));
                self.op(Instr::Div(a, b))
            }
        }
    }

    fn neg(&mut self, x: Val) -> Val {
        match x {
            Val::Num(a) => Val::Num(-a),
            Val::Slot(s) => self.op(Instr::Neg(s)),
        }
    }

    fn is_zero(v: Val) -> bool {
        v == Val::Num(0.0)
    }
}

/// The outputs' partial derivatives with respect to inputs `wrt` (indices into `[t, x…]`):
/// one program whose outputs are `∂out_i/∂input_wrt[k]`, row-major (i over outputs, k over
/// `wrt`), evaluated on the same inputs as `p`.
pub fn derivatives(p: &Program, wrt: &[usize]) -> Program {
    let n_in = p.n_inputs;
    let k = wrt.len();
    let mut b = Builder::new(n_in);
    // new slot and derivative row of every old slot
    let total = n_in + p.code.len();
    let mut slot_of = vec![0u32; total];
    let mut d: Vec<Vec<Val>> = Vec::with_capacity(total);
    for (i, slot) in slot_of.iter_mut().enumerate().take(n_in) {
        *slot = i as u32;
        d.push(
            wrt.iter()
                .map(|&w| Val::Num(if w == i { 1.0 } else { 0.0 }))
                .collect(),
        );
    }
    for (ci, ins) in p.code.iter().enumerate() {
        let q = b.emit(ins.remap(|s| slot_of[s as usize]));
        slot_of[n_in + ci] = q;
        let qv = Val::Slot(q);
        let val = |s: u32| Val::Slot(slot_of[s as usize]);
        let mut row = Vec::with_capacity(k);
        for j in 0..k {
            let dv = |s: u32| d[s as usize][j];
            let mut a = Alg { b: &mut b };
            use Instr::*;
            let r = match *ins {
                Const(_) | Sign(_) => Val::Num(0.0),
                Add(x, y) => a.add(dv(x), dv(y)),
                Sub(x, y) => a.sub(dv(x), dv(y)),
                Mul(x, y) => {
                    let l = a.mul(dv(x), val(y));
                    let r = a.mul(val(x), dv(y));
                    a.add(l, r)
                }
                Div(x, y) => {
                    let t = a.mul(qv, dv(y));
                    let num = a.sub(dv(x), t);
                    a.div(num, val(y))
                }
                Neg(x) => a.neg(dv(x)),
                Pow(x, y) => {
                    let (dx, dy) = (dv(x), dv(y));
                    let mut acc = Val::Num(0.0);
                    if !Alg::is_zero(dx) {
                        // y · x^(y − 1) · dx (defined for x ≤ 0 where y is whole)
                        let ym1 = a.sub(val(y), Val::Num(1.0));
                        let (xs, es) = (a.s(val(x)), a.s(ym1));
                        let pw = a.op(Pow(xs, es));
                        let t = a.mul(val(y), pw);
                        acc = a.mul(t, dx);
                    }
                    if !Alg::is_zero(dy) {
                        let xs = a.s(val(x));
                        let ln = a.op(Ln(xs));
                        let t = a.mul(qv, ln);
                        let t = a.mul(t, dy);
                        acc = a.add(acc, t);
                    }
                    acc
                }
                PowI(x, e) => {
                    let dx = dv(x);
                    if Alg::is_zero(dx) {
                        Val::Num(0.0)
                    } else {
                        let pw = match e - 1 {
                            0 => Val::Num(1.0),
                            1 => val(x),
                            m => {
                                let xs = a.s(val(x));
                                a.op(PowI(xs, m))
                            }
                        };
                        let t = a.mul(Val::Num(e as f64), pw);
                        a.mul(t, dx)
                    }
                }
                Atan2(y, x) => {
                    // d atan2(y, x) = (x dy − y dx) / (x² + y²)
                    let (dy, dx) = (dv(y), dv(x));
                    if Alg::is_zero(dy) && Alg::is_zero(dx) {
                        Val::Num(0.0)
                    } else {
                        let l = a.mul(val(x), dy);
                        let r = a.mul(val(y), dx);
                        let num = a.sub(l, r);
                        let xx = a.mul(val(x), val(x));
                        let yy = a.mul(val(y), val(y));
                        let den = a.add(xx, yy);
                        a.div(num, den)
                    }
                }
                Min(x, y) | Max(x, y) => {
                    let (dx, dy) = (dv(x), dv(y));
                    if dx == dy {
                        dx
                    } else {
                        // min: x ≤ y picks x; max: y ≤ x picks x
                        let (l, r) = match *ins {
                            Min(..) => (val(x), val(y)),
                            _ => (val(y), val(x)),
                        };
                        let (l, r) = (a.s(l), a.s(r));
                        let (dx, dy) = (a.s(dx), a.s(dy));
                        a.op(PickLe(l, r, dx, dy))
                    }
                }
                PickLe(l, r, x, y) => {
                    let (dx, dy) = (dv(x), dv(y));
                    if dx == dy {
                        dx
                    } else {
                        let (l, r) = (a.s(val(l)), a.s(val(r)));
                        let (dx, dy) = (a.s(dx), a.s(dy));
                        a.op(PickLe(l, r, dx, dy))
                    }
                }
                Sin(x) => {
                    let xs = a.s(val(x));
                    let c = a.op(Cos(xs));
                    a.mul(c, dv(x))
                }
                Cos(x) => {
                    let xs = a.s(val(x));
                    let s = a.op(Sin(xs));
                    let t = a.mul(s, dv(x));
                    a.neg(t)
                }
                Tan(x) => {
                    let qq = a.mul(qv, qv);
                    let t = a.add(Val::Num(1.0), qq);
                    a.mul(t, dv(x))
                }
                Exp(x) => a.mul(qv, dv(x)),
                Ln(x) => a.div(dv(x), val(x)),
                Sqrt(x) => {
                    let t = a.div(dv(x), qv);
                    a.mul(Val::Num(0.5), t)
                }
                Abs(x) => {
                    let xs = a.s(val(x));
                    let sg = a.op(Sign(xs));
                    a.mul(sg, dv(x))
                }
            };
            row.push(r);
        }
        d.push(row);
    }
    let mut outputs = Vec::with_capacity(p.outputs.len() * k);
    for &o in &p.outputs {
        for j in 0..k {
            let v = d[o as usize][j];
            outputs.push(b.slot(v));
        }
    }
    Program::pruned(n_in, b.code, outputs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::expr::compile;

    fn s(v: &[&str]) -> Vec<String> {
        v.iter().map(|x| x.to_string()).collect()
    }

    #[test]
    fn a_linear_system_has_a_constant_jacobian_without_code() {
        let p = compile(&s(&["v", "-4*x"]), &s(&["x", "v"]), &[]).unwrap();
        let j = derivatives(&p, &[1, 2]);
        let mut out = [9.0; 4];
        j.eval(0.3, &[5.0, 7.0], &mut out);
        assert_eq!(out, [0.0, 1.0, -4.0, 0.0]);
        // two constants (0 shared, 1, −4): nothing is computed at run time
        assert!(j.len() <= 3, "{j:?}");
    }

    #[test]
    fn rules_on_one_variable() {
        let cases: [(&str, fn(f64) -> f64); 10] = [
            ("sin(x)*x", |x| x.cos() * x + x.sin()),
            ("exp(2*x)", |x| 2.0 * (2.0 * x).exp()),
            ("ln(x)/x", |x| (1.0 - x.ln()) / (x * x)),
            ("sqrt(x)", |x| 0.5 / x.sqrt()),
            ("x^3", |x| 3.0 * x * x),
            ("x^2.5", |x| 2.5 * x.powf(1.5)),
            ("2^x", |x| 2f64.powf(x) * 2f64.ln()),
            ("tan(x)", |x| 1.0 / (x.cos() * x.cos())),
            ("atan2(x, 2)", |x| 2.0 / (4.0 + x * x)),
            ("abs(x - 1) + max(x, 0.5) + min(x, 0.5)", |x| {
                (x - 1.0).signum()
                    + if x >= 0.5 { 1.0 } else { 0.0 }
                    + if x <= 0.5 { 1.0 } else { 0.0 }
            }),
        ];
        for (src, d) in cases {
            let p = compile(&s(&[src]), &s(&["x"]), &[]).unwrap();
            let j = derivatives(&p, &[1]);
            for x in [0.3, 0.7, 1.9] {
                let mut out = [0.0];
                j.eval(0.0, &[x], &mut out);
                assert!(
                    (out[0] - d(x)).abs() < 1e-14 * (1.0 + d(x).abs()),
                    "{src} at {x}: {} vs {}",
                    out[0],
                    d(x)
                );
            }
        }
    }

    #[test]
    fn time_derivative_of_a_forced_term() {
        let p = compile(&s(&["-x + cos(3*t)"]), &s(&["x"]), &[]).unwrap();
        let dt = derivatives(&p, &[0]);
        let mut out = [0.0];
        dt.eval(0.4, &[2.0], &mut out);
        assert!((out[0] + 3.0 * (1.2f64).sin()).abs() < 1e-15);
    }
}
