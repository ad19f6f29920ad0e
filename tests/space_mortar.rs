//! Joints with strength in 3D (cohesion c and a tension cut-off ft, shared by a contact's
//! corners by their tributary areas): a box on its base pushed sideways and a stack of two
//! boxes in bending against their closed forms, by limit analysis (peak strengths) and by the
//! explicit solver (brittle joints, which lose both at their first failure); and a running-bond
//! wall with mortar pushed in its plane against the same wall analysed in the plane.

mod common;

use masonry_dem::explicit::{solve_3d, ExplicitOptions};
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{limit_analysis, limit_analysis_3d, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::results::Status;
use masonry_dem::space::{Box3, LiveLoad3, Model3, ModelSpec3};

const G: f64 = 10.0;
const RHO: f64 = 2000.0;

fn mortar(mu: f64, c: f64, ft: f64) -> JointLaw {
    JointLaw { friction: mu, dilatancy: mu, cohesion: c, tensile_strength: ft, normal_stiffness: 1e9, shear_stiffness: 1e9, ..JointLaw::default() }
}

fn model(blocks: Vec<Box3>, joints: JointLaws) -> Model3 {
    Model3::new(&ModelSpec3 { blocks, density: RHO, gravity: G, joints, live: LiveLoad3::HorizontalWeight { direction: 0.0 }, ..ModelSpec3::default() }).unwrap()
}

/// The limit multiplier, the interior point run to 1e-12; asserts a collapse at peak strengths.
fn limit(m: &Model3) -> f64 {
    let r = limit_analysis_3d(m, &LimitOptions { tolerance: 1e-12, ..LimitOptions::default() }).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    assert!(r.certificate.unwrap().peak_strengths);
    r.collapse_multiplier
}

/// The explicit collapse multiplier; asserts a collapse.
fn explicit(m: &Model3) -> f64 {
    let r = solve_3d(m, &ExplicitOptions::default()).unwrap();
    assert_eq!(r.status, Status::Collapse, "{:?}", r.error);
    eprintln!("explicit {:.6} bracket {:?}, {} steps", r.collapse_multiplier, r.bracket, r.iterations);
    r.collapse_multiplier
}

fn close(got: f64, want: f64, rel: f64, what: &str) {
    assert!((got - want).abs() <= rel * want.abs(), "{what}: got {got:.12}, closed form {want:.12} ({:+.2e})", got / want - 1.0);
}

#[test]
fn a_box_with_mortar_on_its_base_slides_at_c_a_plus_mu_w() {
    // a flat box, b x d x h = 1.0 x 0.8 x 0.004 m (W = 64 N), friction 0.6, c = 50 Pa (c A = 40 N),
    // ft = 20 Pa: it slides at lambda W = c A + mu W (overturning needs lambda >= b / h)
    let (b, d, h, mu, c, ft) = (1.0, 0.8, 0.004, 0.6, 50.0, 20.0);
    let m = model(vec![Box3::new(0.0, 0.0, 0.0, b, d, h)], JointLaws::uniform(mortar(mu, c, ft)));
    let w = RHO * G * b * d * h;
    let want = (c * b * d + mu * w) / w;
    close(limit(&m), want, 1e-9, "sliding, limit analysis");
    // brittle: the first corner to fail breaks the joint, the lightest-pressed one (the live
    // load's moment lightens the heel by lambda W h / (2 b) over the corners' pair): at
    // lambda = (c A + mu W) / (W (1 + mu h / b)), 0.24% below the peak
    close(explicit(&m), want, 1e-2, "sliding, explicit");
}

#[test]
fn a_box_with_mortar_on_its_base_overturns_on_its_tensile_strength() {
    // b x d x h = 0.4 x 0.5 x 1.2 m (W = 4800 N), friction 1, c = 50 kPa, ft = 12 kPa (ft A = 2400
    // N, below c A / mu): rocking about its toe, the heel's corners pull ft A / 2 at the lever b:
    // lambda W h / 2 = W b / 2 + ft A b / 2, lambda = b (W + ft A) / (W h); sliding needs
    // lambda >= (c A + mu W) / W = 3.1
    let (b, d, h, mu, c, ft) = (0.4, 0.5, 1.2, 1.0, 5e4, 1.2e4);
    let m = model(vec![Box3::new(0.0, 0.0, 0.0, b, d, h)], JointLaws::uniform(mortar(mu, c, ft)));
    let (w, a) = (RHO * G * b * d * h, b * d);
    let want = b * (w + ft * a) / (w * h);
    close(limit(&m), want, 1e-9, "overturning, limit analysis");
    // the corners' linear elastic distribution puts the heel's pair at ft A / 2 at the same
    // moment: the brittle joint breaks there, and the dry box cannot hold it
    close(explicit(&m), want, 1e-2, "overturning, explicit");
}

#[test]
fn a_stack_of_two_boxes_with_mortar_fails_in_bending_at_the_weaker_joint() {
    // two boxes b x d x hb = 0.3 x 0.4 x 0.6 m (W = 1440 N each), friction 1, c = 100 kPa: the
    // stack rocks on its base (its heel pulling h_base / 2 at the lever b) at
    // lambda_B = b (W + h_base / 2) / (2 W hb), or the upper box on the bed joint at
    // lambda_A = b (W + h_bed) / (W hb), h = ft A each; both mechanisms together give no less
    let (b, d, hb) = (0.3, 0.4, 0.6);
    let (w, a) = (RHO * G * b * d * hb, b * d);
    let blocks = vec![Box3::new(0.0, 0.0, 0.0, b, d, hb), Box3::new(0.0, 0.0, hb, b, d, 2.0 * hb)];
    // the same mortar everywhere (ft = 6 kPa: h = 720 N): the base joint, lambda_B
    let ft = 6e3;
    let m = model(blocks.clone(), JointLaws::uniform(mortar(1.0, 1e5, ft)));
    let (la, lb) = (b * (w + ft * a) / (w * hb), b * (w + 0.5 * ft * a) / (2.0 * w * hb));
    assert!(lb < la);
    close(limit(&m), lb, 1e-9, "the stack on its base, limit analysis");
    close(explicit(&m), lb, 1e-2, "the stack on its base, explicit");
    // a base joint twelve times as strong in tension (ft A = 8640 N, below c A / mu): the bed
    // joint, lambda_A
    let (ft_bed, ft_base) = (6e3, 7.2e4);
    let joints = JointLaws { base: Some(mortar(1.0, 1e5, ft_base)), ..JointLaws::uniform(mortar(1.0, 1e5, ft_bed)) };
    let m = model(blocks, joints);
    let (la, lb) = (b * (w + ft_bed * a) / (w * hb), b * (w + 0.5 * ft_base * a) / (2.0 * w * hb));
    assert!(la < lb);
    close(limit(&m), la, 1e-9, "the upper box on the bed joint, limit analysis");
    close(explicit(&m), la, 1e-2, "the upper box on the bed joint, explicit");
}

#[test]
fn a_running_bond_wall_with_mortar_pushed_in_its_plane_is_the_planes() {
    // Ferris and Tin-Loi's wall 1 (2 m x 6 courses of 0.4 x 0.175 m blocks, 0.3 m thick) with
    // mortar, friction 0.65, c = 20 kPa, ft = 8 kPa (below c / mu): each 3D contact's four
    // corners carry a quarter of c A and ft A each, two at each end of the plane's interface,
    // whose domain is its two ends' (ft <= c / mu): the plane's program in the wall's plane
    let law = mortar(0.65, 2e4, 8e3);
    let rects = common::ferris_blocks(6);
    let t = 0.3;
    let plane = Model::new(ModelSpec {
        blocks: masonry_dem::geometry::polygons(rects.clone()),
        thickness: t,
        density: RHO,
        gravity: G,
        joints: JointLaws::uniform(law),
        ..ModelSpec::default()
    })
    .unwrap();
    let l2 = limit_analysis(&plane, &LimitOptions { tolerance: 1e-12, ..LimitOptions::default() }).unwrap();
    assert_eq!(l2.status, Status::Collapse, "{:?}", l2.error);
    let boxes = rects.iter().map(|r| Box3::new(r.x0, 0.0, r.y0, r.x1, t, r.y1)).collect();
    let l3 = limit(&model(boxes, JointLaws::uniform(law)));
    eprintln!("wall 1 with mortar: plane {:.10}, 3D {l3:.10}", l2.collapse_multiplier);
    close(l3, l2.collapse_multiplier, 1e-7, "wall 1 with mortar extruded");
}
