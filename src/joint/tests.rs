//! Unit tests of the joint law's internals.

use super::*;

/// [`return_map`], one copy for all the tests: inlined at each of their call sites (it
/// is `inline(always)`), it made this module's test build take over nine minutes.
#[inline(never)]
fn map(law: &JointLaw, sec: &Section, e: [f64; 3], committed: &JointState, opts: MapOptions) -> (Response, u8) {
    return_map(law, sec, e, committed, &opts)
}

/// A tiny xorshift generator: the same numbers on every run.
fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut x = seed;
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// The laws of the mapping tests: dry, associative, dilatant, brittle, softening, with all
/// four faces meeting at one point (c = mu ft), and with a stiffer shear.
fn laws() -> [JointLaw; 7] {
    let base = JointLaw { friction: 0.65, ..JointLaw::default() };
    [
        base,
        JointLaw { dilatancy: 0.65, ..base },
        JointLaw { dilatancy: 0.3, ..base },
        JointLaw { cohesion: 2e4, tensile_strength: 1e4, dilatancy: 0.2, ..base },
        JointLaw { cohesion: 2e4, tensile_strength: 1e4, fracture_energy_tension: 10.0, fracture_energy_shear: 50.0, ..base },
        JointLaw { cohesion: 0.65e4, tensile_strength: 1e4, dilatancy: 0.65, ..base },
        JointLaw { shear_stiffness: 4e9, dilatancy: 0.4, ..base },
    ]
}

/// Random jumps of up to 1e-5 m (forces up to about 4e4 N against strengths of 4e3 to
/// 8e3 N), some components zero, and a random plastic history.
fn random_case(r: &mut impl FnMut() -> f64) -> ([f64; 3], JointState) {
    let mut e = [1e-5 * r(), 1e-5 * r(), 5e-5 * r()];
    for x in e.iter_mut() {
        if r() > 0.8 {
            *x = 0.0;
        }
    }
    (e, JointState { plastic: [1e-6 * r(), 1e-6 * r(), 0.0], ..JointState::default() })
}

#[test]
fn a_warm_start_and_prepared_constants_give_the_force_and_history_of_the_ordered_enumeration() {
    let (laws, sec) = (laws(), Section::new(0.4, 1.0));
    let mut r = rng(7);
    let mut worst: [f64; 3] = [0.0; 3];
    for law in &laws {
        let prep = Prepared::new(law, &sec);
        for _ in 0..20000 {
            let (e, committed) = random_case(&mut r);
            let forces = MapOptions { tangent: false, ..MapOptions::default() };
            let (cold, set) = map(law, &sec, e, &committed, forces);
            let scale = cold.force[0].abs() + cold.force[1].abs() + cold.force[2].abs() * 5.0 + 1.0;
            for warm in 1..15u8 {
                let (w, wset) = map(law, &sec, e, &committed, MapOptions { warm, ..forces });
                // the prepared constants change nothing, bit for bit
                let (wp, wpset) = return_map(law, &sec, e, &committed, &MapOptions { prepared: Some(&prep), warm, strict: false, tangent: false });
                assert_eq!((wp.force.map(f64::to_bits), wp.state.plastic.map(f64::to_bits)), (w.force.map(f64::to_bits), w.state.plastic.map(f64::to_bits)));
                assert_eq!((wp.state.opening.to_bits(), wp.state.slip.to_bits(), wp.state.broken, wp.flags, wpset), (w.state.opening.to_bits(), w.state.slip.to_bits(), w.state.broken, w.flags, wset));
                let df = (0..3).map(|c| (w.force[c] - cold.force[c]).abs()).fold(0.0, f64::max) / scale;
                let dp = (0..3).map(|c| (w.state.plastic[c] - cold.state.plastic[c]).abs()).fold(0.0, f64::max) / 1e-5;
                let dk = ((w.state.opening - cold.state.opening).abs() + (w.state.slip - cold.state.slip).abs()) / 1e-5;
                worst = [worst[0].max(df), worst[1].max(dp), worst[2].max(dk)];
                if df > 1e-9 || dp > 1e-9 || dk > 1e-9 {
                    panic!("{law:?} e {e:?}: warm {warm} set {wset} {w:?} against set {set} {cold:?}");
                }
            }
        }
    }
    println!("worst relative differences: force {:e} plastic {:e} opening/slip {:e}", worst[0], worst[1], worst[2]);
}

/// The bits of everything a mapping gives: force, history, flags, tangent and set.
fn bits(r: &Response, set: u8) -> Vec<u64> {
    let mut v: Vec<u64> = r.force.iter().chain(&r.state.plastic).chain(r.tangent.iter().flatten()).map(|x| x.to_bits()).collect();
    v.extend([r.state.opening.to_bits(), r.state.slip.to_bits(), r.state.broken as u64, r.flags as u64, set as u64]);
    v
}

#[test]
fn a_strict_warm_set_with_prepared_constants_gives_the_ordered_enumerations_bits_tangent_included() {
    let (laws, sec) = (laws(), Section::new(0.4, 1.0));
    let mut r = rng(11);
    for law in &laws {
        let kinds = Kinds::new([(0, law, &sec)], 1);
        let prep = kinds.prepared(0).unwrap();
        for _ in 0..20000 {
            let (e, committed) = random_case(&mut r);
            let (cold, set) = map(law, &sec, e, &committed, MapOptions::default());
            assert_eq!(bits(&cold, set), bits(&return_map(law, &sec, e, &committed, &MapOptions::default()).0, set));
            if set == 0 {
                assert_eq!(elastic_tangent(law, &sec), cold.tangent);
            }
            for warm in 0..15u8 {
                for prepared in [None, Some(prep)] {
                    let opts = MapOptions { prepared, warm, strict: true, tangent: true };
                    let (w, wset) = map(law, &sec, e, &committed, opts);
                    assert_eq!(bits(&w, wset), bits(&cold, set), "{law:?} e {e:?} warm {warm}");
                    // without the tangent: the same force, history, flags and set
                    let (f, fset) = map(law, &sec, e, &committed, MapOptions { tangent: false, ..opts });
                    assert_eq!(bits(&Response { tangent: cold.tangent, ..f }, fset), bits(&cold, set));
                }
                // the set found, given back as the warm set without margins, is taken again
                if warm == set && set != 0 {
                    let (w, wset) = map(law, &sec, e, &committed, MapOptions { warm, ..MapOptions::default() });
                    assert_eq!(bits(&w, wset), bits(&cold, set));
                }
            }
        }
    }
}

/// At the apex of a dry joint (tan psi > 0) the multipliers are not unique, and a warm set 7
/// or 11 is taken only where it is the ordered enumeration's choice (`apex_set`): trials in
/// the cone of the flow columns, generic and next to its rays, its faces and the planes of
/// its pairs (down to 1e-15 of the trial), mapped with every warm set, strict or not, with
/// and without prepared constants: the bits of the ordered enumeration, tangent included.
#[test]
fn a_warm_set_at_the_apex_is_taken_only_where_the_ordered_enumeration_takes_it() {
    let sec = Section::new(0.4, 1.0);
    let mut r = rng(23);
    let mut taken = 0;
    let mut total = 0;
    // the dry dilatant laws, and two with flow columns nearer each other: a small dilatancy
    // and a soft shear
    let base = JointLaw { friction: 0.65, ..JointLaw::default() };
    let extra = [JointLaw { dilatancy: 0.02, ..base }, JointLaw { dilatancy: 0.65, shear_stiffness: 1e7, ..base }];
    for law in laws().iter().filter(|l| l.dilatancy > 0.0 && !l.is_strong()).chain(&extra) {
        let prep = Prepared::new(law, &sec);
        let faces = Faces::new(law, &sec, 0.0, 0.0);
        let d = stiffness(law, &sec);
        for i in 0..20000 {
            // multipliers of the four flow columns: random, some near zero, some pairs near
            // equal (on the plane of g_2, g_3 where r_0 = r_1 in set 7's terms)
            let mut lam = [r().abs(), r().abs(), r().abs(), r().abs()];
            let tiny = [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3][i % 6];
            match (i / 6) % 5 {
                0 => {}
                1 => lam[(i / 30) % 4] = tiny * r().abs(),
                2 => {
                    lam[(i / 30) % 4] = tiny * r().abs();
                    lam[(i / 120) % 4] = tiny * r().abs();
                }
                3 => lam[1] = lam[0] * (1.0 + tiny * r()),
                _ => {
                    lam[3] = tiny * r().abs();
                    lam[1] = lam[0] * (1.0 + tiny * r());
                }
            }
            let t: [f64; 3] = std::array::from_fn(|c| (0..4).map(|j| 1e-6 * lam[j] * d[c] * faces.m(j)[c]).sum());
            let committed = JointState { plastic: [1e-6 * r(), 1e-6 * r(), 0.0], ..JointState::default() };
            let e: [f64; 3] = std::array::from_fn(|c| t[c] / d[c] + committed.plastic[c]);
            let (cold, set) = map(law, &sec, e, &committed, MapOptions::default());
            for warm in [7u8, 11, 13, 14, 3, 12, set] {
                for strict in [false, true] {
                    for prepared in [None, Some(&prep)] {
                        let opts = MapOptions { prepared, warm, strict, tangent: true };
                        let (w, wset) = map(law, &sec, e, &committed, opts);
                        assert_eq!(bits(&w, wset), bits(&cold, set), "{law:?} lam {lam:?} warm {warm} strict {strict}");
                    }
                }
            }
            // how often the shortcut is taken
            if set == 7 || set == 11 {
                total += 1;
                let tr: [f64; 3] = std::array::from_fn(|c| d[c] * (e[c] - committed.plastic[c]));
                let tol = kt_tolerance(force_scale(&tr, &sec), &faces);
                let ft: [f64; 4] = std::array::from_fn(|j| faces.f(j, &tr));
                let problem = Trial { faces: &faces, prep: Some(&prep), trial: &tr, f_trial: &ft, g_all: &prep.g_all, dm: &prep.dm, tol };
                taken += apex_return(set, &problem).is_some() as usize;
            }
        }
    }
    // the generic fifth of the cases at least
    assert!(taken * 5 > total, "the shortcut taken in {taken} of {total} returns to the apex");
    println!("shortcut taken in {taken} of {total} returns to the apex by set 7 or 11");
}
