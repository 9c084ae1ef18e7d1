//! Stability of re-layouts: resizing one room of a 7-room house keeps the other rooms where
//! they were (mean displacement under 0.5 m), through the same tool an agent calls.

use scenesmith::agents::Role;
use scenesmith::layout::state::LayoutState;
use scenesmith::layout::tools::toolbox;
use serde_json::json;

const FITNESS: &str = "A small fitness studio with a workout area, a yoga room, a locker room, \
    a reception, an office, a storage room, and a bathroom.";

#[test]
fn resizing_one_room_keeps_the_others_in_place() {
    let tools = toolbox();
    let base = LayoutState::from_prompt(FITNESS, 3);
    let spec = base.spec.clone().unwrap();
    assert_eq!(spec.rooms.len(), 7);
    let mut means = Vec::new();
    for r in &spec.rooms {
        let mut s = base.clone();
        // Grow the room by about 20% of its area.
        let (w, d) = (r.size[0] * 1.1, r.size[1] * 1.1);
        tools
            .call(
                &mut s,
                Role::Designer,
                "resize_room",
                json!({"room": r.id, "width_m": w, "depth_m": d}),
            )
            .unwrap();
        let mean = s
            .placement
            .mean_displacement(&base.placement, &[r.id.as_str()]);
        eprintln!("{}: mean displacement of the others {mean:.3} m", r.id);
        let v = s.validation();
        assert!(v.ok, "{}: {:?}", r.id, v.errors);
        // Each resize on its own keeps the other rooms within 0.5 m on average.
        assert!(mean < 0.5, "{}: {mean:.3} m", r.id);
        means.push(mean);
    }
    let avg = means.iter().sum::<f64>() / means.len() as f64;
    eprintln!("average {avg:.3}");
    assert!(avg < 0.25, "{means:?}");
}
