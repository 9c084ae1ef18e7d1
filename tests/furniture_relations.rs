//! Furniture the prompt relates to other furniture stands where the words put it: two sofas
//! facing each other with a coffee table between them, nightstands flanking a bed, a coffee
//! table in front of a sofa (the built-in designer's `place_relative` and `place_facing`).

use scenesmith::agents::Backend;
use scenesmith::pipeline::build_scene;
use scenesmith::scene::SceneObject;

/// (centre x, y of the object's origin, heading: the yaw of its front, +Y at yaw 0).
fn pose(o: &SceneObject) -> (f64, f64, f64) {
    let t = o.world_from_object.translation();
    (t.x, t.y, o.world_from_object.yaw())
}

/// `p` in the frame of an object at (x, y, yaw): (to its right, to its front).
fn local(of: (f64, f64, f64), p: (f64, f64)) -> (f64, f64) {
    let (dx, dy) = (p.0 - of.0, p.1 - of.1);
    let (s, c) = of.2.sin_cos();
    (c * dx + s * dy, -s * dx + c * dy)
}

fn wrap(a: f64) -> f64 {
    let mut a = a % std::f64::consts::TAU;
    if a > std::f64::consts::PI {
        a -= std::f64::consts::TAU;
    } else if a <= -std::f64::consts::PI {
        a += std::f64::consts::TAU;
    }
    a
}

fn of_category<'a>(objects: &'a [SceneObject], category: &str) -> Vec<&'a SceneObject> {
    objects.iter().filter(|o| o.category == category).collect()
}

#[test]
fn two_sofas_face_each_other_with_the_coffee_table_between_them() {
    let prompt = "A family room with two sofas facing each other and a coffee table between \
                  them.";
    let (state, _) = build_scene(prompt, 5, "facing_sofas", &Backend::Builtin).unwrap();
    let objects = &state.scene.objects;
    let sofas = of_category(objects, "sofa");
    assert_eq!(sofas.len(), 2, "two sofas");
    let (a, b) = (pose(sofas[0]), pose(sofas[1]));
    assert!(
        (wrap(a.2 - b.2).abs() - std::f64::consts::PI).abs() < 0.05,
        "headings {:.2} and {:.2} are not opposite",
        a.2,
        b.2
    );
    // Each one's front looks at the other (straight across, or slid sideways by less than
    // half a sofa's width where the room asks for it).
    for (from, to) in [(a, b), (b, a)] {
        let (side, ahead) = local(from, (to.0, to.1));
        assert!(
            ahead > 1.0 && side.abs() < 0.6,
            "the other sofa is at {side:.2}, {ahead:.2}"
        );
    }
    let tables = of_category(objects, "coffee_table");
    assert_eq!(tables.len(), 1, "one coffee table");
    let t = pose(tables[0]);
    let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
    let off = ((t.0 - mid.0).powi(2) + (t.1 - mid.1).powi(2)).sqrt();
    assert!(
        off < 0.2,
        "the coffee table is {off:.2} m from the sofas' midpoint"
    );
}

#[test]
fn two_nightstands_flank_the_bed_with_their_backs_in_line() {
    let prompt = "A bedroom with a double bed and two nightstands flanking the bed.";
    let (state, _) = build_scene(prompt, 2, "flanking", &Backend::Builtin).unwrap();
    let objects = &state.scene.objects;
    let beds: Vec<_> = objects
        .iter()
        .filter(|o| o.category.ends_with("bed"))
        .collect();
    assert_eq!(beds.len(), 1, "one bed");
    let bed = pose(beds[0]);
    let stands = of_category(objects, "nightstand");
    assert_eq!(stands.len(), 2, "two nightstands");
    let sides: Vec<f64> = stands
        .iter()
        .map(|n| {
            let p = pose(n);
            assert!(
                wrap(p.2 - bed.2).abs() < 0.05,
                "{} is turned from the bed",
                n.id
            );
            let (side, ahead) = local(bed, (p.0, p.1));
            // Beside the bed's head end, not at its foot.
            assert!(
                ahead < 0.0,
                "{} stands {ahead:.2} m ahead of the bed's centre",
                n.id
            );
            side
        })
        .collect();
    assert!(
        sides.iter().any(|s| *s > 0.5) && sides.iter().any(|s| *s < -0.5),
        "the nightstands are not on both sides: {sides:?}"
    );
}

#[test]
fn a_coffee_table_in_front_of_the_sofa_faces_it() {
    let prompt = "A small living room with a sofa and a coffee table in front of the sofa.";
    let (state, _) = build_scene(prompt, 1, "in_front", &Backend::Builtin).unwrap();
    let objects = &state.scene.objects;
    let sofa = pose(of_category(objects, "sofa")[0]);
    let tables = of_category(objects, "coffee_table");
    assert_eq!(tables.len(), 1, "one coffee table");
    let t = pose(tables[0]);
    let (side, ahead) = local(sofa, (t.0, t.1));
    assert!(
        ahead > 0.5 && ahead < 1.6 && side.abs() < 0.1,
        "the coffee table is at {side:.2}, {ahead:.2} in the sofa's frame"
    );
}
