//! How much clutter one supporting piece holds: the room's usual small objects for it, sized to
//! the surfaces the built piece has (its top, its open shelves, and the drawers and shelves
//! behind its doors).
//!
//! The plan knows a room type's usual objects per kind of parent, but not how large the
//! parent turned out: a 2.4 m counter and a 0.6 m one get the same list. Here each surface
//! takes a share of its area in objects (`COVERAGE`, scaled by the prompt's density word), the
//! count follows from the objects' typical footprints, and the plan's defaults for the piece
//! grow to that count. What the prompt asked for is never changed: explicit wants keep their
//! counts, and a parent the prompt filled itself gets no defaults (the plan already left it
//! out).

use crate::assets::router::naming::footprint;
use crate::plan::{
    Arrangement, Want, clutter_factor, kept_in_numbers, one_per_parent, split_counts,
};
use crate::prompt::Density;
use crate::scene::{AssetRecord, SurfaceRecord};

/// Share of a surface's area that the usual clutter covers, by kind of surface: a table or
/// dresser top, an open shelf, a seat or mattress, a drawer or a shelf behind a door.
struct Coverage {
    top: f64,
    shelf: f64,
    seat: f64,
    enclosed: f64,
}

const COVERAGE: Coverage = Coverage {
    top: 0.3,
    shelf: 0.4,
    seat: 0.1,
    enclosed: 0.4,
};

/// Most default small objects one piece gets at the usual density, scaled like the coverage
/// (a long bookcase is not filled with 150 books: each one is a body the physics steps have to
/// carry).
pub const MAX_PER_PIECE: u32 = 36;

/// Behind a door or in a drawer: a surface of a moving link (a drawer), or any surface but
/// the top of an articulated piece (shelves behind its doors).
pub fn is_enclosed(rec: &AssetRecord, s: &SurfaceRecord) -> bool {
    s.link != rec.root_link
        || !(rec.joints.is_empty() || s.id.starts_with("top") || s.id == "basin")
}

/// Area the usual clutter covers on one piece, m²: `(open, enclosed)`.
pub fn clutter_area(rec: &AssetRecord, density: Option<Density>) -> (f64, f64) {
    let scale = clutter_factor(density);
    let (mut open, mut enclosed) = (0.0, 0.0);
    for s in &rec.surfaces {
        let area = s.size[0] * s.size[1];
        if is_enclosed(rec, s) {
            enclosed += (COVERAGE.enclosed * scale).min(0.8) * area;
            continue;
        }
        let share = match s.id.as_str() {
            // A wet basin (a bathtub's, a sink's) is kept clear: it may take what the rest of
            // the piece cannot hold, but the usual clutter is not sized to it.
            "basin" => continue,
            "seat" | "chaise" => COVERAGE.seat,
            id if id.starts_with("shelf") || id.starts_with("upper") || id.starts_with("step") => {
                COVERAGE.shelf
            }
            _ => COVERAGE.top,
        };
        open += (share * scale).min(0.8) * area;
    }
    (open, enclosed)
}

/// How many objects of `nouns` (mixed as `split_counts` mixes them) cover `area` m²: when
/// the first is a thing kept in numbers it is half of them (a bookcase's books), so the mean
/// footprint weighs it by half.
fn count_for(area: f64, nouns: &[&str], single: impl Fn(&str) -> bool) -> u32 {
    if nouns.is_empty() || area <= 0.0 {
        return 0;
    }
    let mean_of = |ns: &[&str]| ns.iter().map(|n| footprint(n)).sum::<f64>() / ns.len() as f64;
    let mean = match nouns {
        [first, rest @ ..]
            if !rest.is_empty()
                && !single(first)
                && kept_in_numbers(crate::words::lexicon(), first) =>
        {
            0.5 * footprint(first) + 0.5 * mean_of(rest)
        }
        _ => mean_of(nouns),
    };
    (area / mean).floor() as u32
}

/// Default small objects of one room at the usual density: every one is a body that
/// settling and the stability check simulate, and a room past this costs minutes.
pub const ROOM_DEFAULTS: u32 = 80;

/// How many default small objects one room may get at `density`: `ROOM_DEFAULTS` scaled like
/// the coverage.
pub fn room_budget(density: Option<Density>) -> u32 {
    (f64::from(ROOM_DEFAULTS) * clutter_factor(density)).round() as u32
}

/// Default small objects a room aims for at the usual density when its pieces have few
/// surfaces (a home office of a desk and a bookshelf): their surfaces are then filled more
/// densely, up to [`MAX_FLOOR_GROWTH`] times the usual coverage.
pub const ROOM_FLOOR: u32 = 60;

/// Most a room's coverage grows to reach [`ROOM_FLOOR`].
pub const MAX_FLOOR_GROWTH: f64 = 2.0;

/// [`ROOM_FLOOR`] at `density` (a minimal room aims for half).
pub fn room_floor(density: Option<Density>) -> u32 {
    (f64::from(ROOM_FLOOR) * clutter_factor(density)).round() as u32
}

/// How many default small objects one piece may get at `density`: `MAX_PER_PIECE` scaled
/// like the coverage.
pub fn piece_budget(density: Option<Density>) -> u32 {
    (f64::from(MAX_PER_PIECE) * clutter_factor(density)).round() as u32
}

/// The share of the plan's small objects that piece `rec` gets, with its default (not asked
/// for) objects grown to what its surfaces hold: `items` is the piece's share of one surface
/// group, in plan order. Open defaults grow to the open surfaces, `Stored` ones to the
/// enclosed ones; neither shrinks, and growth takes from `budget`, what the piece may still
/// take over all its groups (`piece_budget`); `share` scales the growth (the room's budget,
/// `room_budget`, split over its pieces).
pub fn sized_to(
    rec: &AssetRecord,
    items: Vec<Want>,
    density: Option<Density>,
    share: f64,
    budget: &mut u32,
) -> Vec<Want> {
    let lex = crate::words::lexicon();
    let (open_area, enclosed_area) = clutter_area(rec, density);
    let single = |noun: &str| one_per_parent(lex, noun);
    let is_default =
        |w: &Want| !w.explicit && matches!(w.arrangement, Arrangement::Free | Arrangement::Stored);
    let mut out: Vec<Want> = items.iter().filter(|w| !is_default(w)).cloned().collect();
    for stored in [false, true] {
        let group: Vec<&Want> = items
            .iter()
            .filter(|w| is_default(w) && (w.arrangement == Arrangement::Stored) == stored)
            .collect();
        if group.is_empty() {
            continue;
        }
        let nouns: Vec<&str> = group.iter().map(|w| w.noun.as_str()).collect();
        let planned: u32 = group.iter().map(|w| w.count).sum();
        let area = if stored { enclosed_area } else { open_area };
        let room = (f64::from(count_for(area, &nouns, single)) * share).round() as u32;
        let want = room.min(*budget).max(planned);
        *budget = budget.saturating_sub(want);
        let counts = split_counts(want, &nouns, single, 1);
        for w in group {
            // A single (a lamp, an appliance) keeps its planned count.
            let count = if single(&w.noun) {
                w.count
            } else {
                counts
                    .iter()
                    .find(|(n, _)| *n == w.noun)
                    .map_or(0, |(_, c)| *c)
                    .max(w.count)
            };
            if count > 0 {
                out.push(Want { count, ..w.clone() });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::procedural::{AssetRequest, build};

    fn record(category: &str) -> AssetRecord {
        let asset = build(&AssetRequest {
            category: category.into(),
            size: None,
            material: None,
            color: None,
            seed: 1,
        })
        .expect("the library builds it");
        asset.record()
    }

    fn default(noun: &str, count: u32, arrangement: Arrangement) -> Want {
        Want {
            noun: noun.into(),
            description: noun.into(),
            count,
            explicit: false,
            at_least: false,
            arrangement,
            height_m: None,
            parent_instance: None,
        }
    }

    /// The plan's storage floor is what the stage's growth can take to the room floor.
    #[test]
    fn the_plans_storage_floor_grows_to_the_room_floor() {
        assert_eq!(
            f64::from(crate::plan::STORAGE_FLOOR) * MAX_FLOOR_GROWTH,
            f64::from(ROOM_FLOOR)
        );
    }

    #[test]
    fn a_dresser_fills_its_drawers_and_a_bookcase_its_shelves() {
        let dresser = sized_to(
            &record("dresser"),
            vec![
                default("vase", 1, Arrangement::Free),
                default("photo frame", 1, Arrangement::Free),
                default("clothes", 2, Arrangement::Stored),
            ],
            None,
            1.0,
            &mut piece_budget(None),
        );
        let clothes = dresser
            .iter()
            .find(|w| w.noun == "clothes")
            .map(|w| w.count);
        // Eight drawers of 0.54 x 0.38 m.
        assert!(clothes.is_some_and(|c| c >= 6), "{dresser:?}");
        let books: u32 = sized_to(
            &record("bookshelf"),
            vec![
                default("book", 12, Arrangement::Free),
                default("photo frame", 2, Arrangement::Free),
            ],
            None,
            1.0,
            &mut piece_budget(None),
        )
        .iter()
        .map(|w| w.count)
        .sum();
        assert!((20..=MAX_PER_PIECE).contains(&books), "{books}");
    }

    #[test]
    fn a_mix_led_by_books_counts_the_books_as_half_and_a_sparse_room_fills_fuller() {
        // Half of a bookcase's objects are books, a twelfth of the footprint of a plant
        // or a folder: the count follows the mix, not the plain mean of the nouns.
        let mix = ["book", "folder", "photo frame", "small plant"];
        let plain = mix.iter().map(|n| footprint(n)).sum::<f64>() / mix.len() as f64;
        let area = 0.5;
        let counted = count_for(area, &mix, |_| false);
        assert!(
            f64::from(counted) > 1.3 * (area / plain).floor(),
            "{counted} vs {}",
            (area / plain).floor()
        );
        // A mix not led by a thing kept in numbers keeps the plain mean.
        let vases = ["vase", "book", "small plant"];
        let plain = vases.iter().map(|n| footprint(n)).sum::<f64>() / 3.0;
        assert_eq!(
            count_for(area, &vases, |_| false),
            (area / plain).floor() as u32
        );
        // The room's growth share (a room below `room_floor`) fills a piece fuller.
        let books = |share: f64| -> u32 {
            sized_to(
                &record("bookshelf"),
                vec![
                    default("vase", 2, Arrangement::Free),
                    default("small plant", 2, Arrangement::Free),
                ],
                None,
                share,
                &mut piece_budget(None),
            )
            .iter()
            .map(|w| w.count)
            .sum()
        };
        assert!(books(MAX_FLOOR_GROWTH) > books(1.0), "{}", books(1.0));
        assert!(room_floor(Some(Density::Minimalist)) < room_floor(None));
        assert!(room_floor(None) < room_budget(None));
    }

    #[test]
    fn a_bathtub_is_filled_on_its_rim_not_in_its_basin() {
        let tub = record("bathtub");
        let rim: f64 = tub
            .surfaces
            .iter()
            .filter(|s| s.id != "basin")
            .map(|s| s.size[0] * s.size[1])
            .sum();
        assert!(tub.surfaces.iter().any(|s| s.id == "basin"));
        let (open, enclosed) = clutter_area(&tub, None);
        assert!(
            (open - COVERAGE.top * rim).abs() < 1e-9,
            "{open} vs rim {rim}"
        );
        assert_eq!(enclosed, 0.0);
    }

    #[test]
    fn a_vanity_counter_beside_its_basin_is_open_and_holds_a_mix() {
        let vanity = record("vanity");
        let tops: Vec<&SurfaceRecord> = vanity
            .surfaces
            .iter()
            .filter(|s| s.id.starts_with("top"))
            .collect();
        assert_eq!(tops.len(), 2, "{:?}", vanity.surfaces);
        assert!(tops.iter().all(|s| !is_enclosed(&vanity, s)));
        assert!(clutter_area(&vanity, None).0 > 0.0);
        // Nobody keeps half a counter of soap dispensers; a bookcase is mostly books.
        let no_single = |_: &str| false;
        let counter = split_counts(
            8,
            &["soap dispenser", "toothbrush", "lotion bottle", "towel"],
            no_single,
            1,
        );
        assert!(counter.iter().all(|(_, c)| *c == 2), "{counter:?}");
        let shelf = split_counts(8, &["book", "vase", "box"], no_single, 1);
        assert_eq!(shelf[0], ("book".to_string(), 4), "{shelf:?}");
    }

    #[test]
    fn asked_for_counts_and_density_words_hold() {
        let mut asked = default("book", 3, Arrangement::Free);
        asked.explicit = true;
        let out = sized_to(
            &record("bookshelf"),
            vec![asked.clone()],
            None,
            1.0,
            &mut piece_budget(None),
        );
        assert_eq!(out, vec![asked]);
        let total = |d: Option<Density>| -> u32 {
            sized_to(
                &record("bookshelf"),
                vec![default("book", 2, Arrangement::Free)],
                d,
                1.0,
                &mut piece_budget(d),
            )
            .iter()
            .map(|w| w.count)
            .sum()
        };
        assert!(total(Some(Density::Minimalist)) < total(None));
        assert!(
            total(Some(Density::Minimalist)) >= 2,
            "never below the plan"
        );
    }
}
