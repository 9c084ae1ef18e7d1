//! Room specifications: what each room is, how big, which rooms it may be entered from and
//! which it should be next to, its materials and windows. Built from a [`HouseBrief`]; the
//! placement search ([`super::search`]) and the architecture ([`super::walls`]) work from it.
//!
//! Sizes start from the room type's typical size, scaled by the prompt's size words within the
//! type's size range, and grow until the room holds what its prompt asks for (furniture
//! footprints plus circulation, and wall length for pieces that stand against walls). A
//! corridor grows with the rooms that open onto it.

use serde::{Deserialize, Serialize};

use super::brief::HouseBrief;
use super::knowledge::{self, Role, knowledge};
use crate::assets::procedural;
use crate::plan::{Arrangement, HouseContext, RoomPlan, plan_house_room, plan_room_of_house};
use crate::prompt;
use crate::scene::IdAllocator;

/// Default wall height, metres.
pub const WALL_HEIGHT: f64 = 2.7;
/// Wall height of buildings with large public rooms, metres.
pub const TALL_WALL_HEIGHT: f64 = 3.0;

/// One room to lay out.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct RoomSpec {
    /// Room id, e.g. `exam_room_1`.
    pub id: String,
    /// Room type (a key of the room registry, [`crate::knowledge::rooms`]).
    pub room_type: String,
    /// What the prompt calls it, e.g. "exam room".
    pub label: String,
    /// Circulation role.
    pub role: Role,
    /// The room's own prompt (its sentences, house-wide style).
    pub prompt: String,
    /// Wanted clear interior size `[long, short]`, metres.
    pub size: [f64; 2],
    /// Smallest acceptable side, metres.
    pub min_side: f64,
    /// Whether the room wants windows.
    pub windows: bool,
    /// Window sill height, metres.
    pub sill: f64,
    /// Floor material.
    pub floor_material: String,
    /// Wall material.
    pub wall_material: String,
    /// For an en-suite: the bedroom it belongs to.
    pub owner: Option<String>,
    /// Rooms this room may be entered from, best first (empty: any neighbour).
    pub parents: Vec<String>,
}

impl RoomSpec {
    /// Clear floor area, m^2.
    pub fn area(&self) -> f64 {
        self.size[0] * self.size[1]
    }
}

/// How two rooms must relate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Link {
    /// Sharing a wall is a plus, nothing more.
    Preferred,
    /// Must share a wall long enough for a door, and get one.
    Door,
    /// Must share a wall, which is removed (open plan).
    Open,
}

/// An adjacency between two rooms.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Adjacency {
    /// One room id.
    pub a: String,
    /// The other room id.
    pub b: String,
    /// What the pair needs.
    pub link: Link,
}

impl Adjacency {
    /// Whether this pair joins `x` and `y` (either order).
    pub fn joins(&self, x: &str, y: &str) -> bool {
        (self.a == x && self.b == y) || (self.a == y && self.b == x)
    }

    /// Whether the pair needs a shared wall.
    pub fn required(&self) -> bool {
        self.link != Link::Preferred
    }
}

/// Everything the placement search and the architecture need.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HouseSpec {
    /// The rooms, in prompt order.
    pub rooms: Vec<RoomSpec>,
    /// Pairs of rooms that should or must be next to each other.
    pub adjacency: Vec<Adjacency>,
    /// Floor to ceiling, metres (one height for the whole house).
    pub wall_height: f64,
    /// The room the exterior door opens into.
    pub entrance: String,
}

impl HouseSpec {
    /// A room by id.
    pub fn room(&self, id: &str) -> Option<&RoomSpec> {
        self.rooms.iter().find(|r| r.id == id)
    }

    /// Index of a room by id.
    pub fn index(&self, id: &str) -> Option<usize> {
        self.rooms.iter().position(|r| r.id == id)
    }

    /// The pair joining `a` and `b`, if any.
    pub fn pair(&self, a: &str, b: &str) -> Option<&Adjacency> {
        self.adjacency.iter().find(|p| p.joins(a, b))
    }

    /// The hub (corridor or hallway) with the most area, if the house has one.
    pub fn hub(&self) -> Option<&RoomSpec> {
        self.rooms
            .iter()
            .filter(|r| r.role == Role::Hub)
            .max_by(|a, b| a.area().total_cmp(&b.area()))
    }
}

/// What a room's contents need: floor area of the pieces and wall length for pieces that
/// stand against walls.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct ContentNeeds {
    /// Sum of furniture footprints, m^2.
    pub floor_m2: f64,
    /// Wall length taken by pieces against walls, metres.
    pub wall_m: f64,
}

fn typical(noun: &str) -> Option<[f64; 3]> {
    let cat = crate::assets::router::naming::category_of(noun).unwrap_or(noun);
    procedural::prior(cat).map(|p| p.typical)
}

/// Floor and wall needs of a room plan, including extra shelving when the small objects do
/// not fit on the planned surfaces.
pub fn content_needs(plan: &RoomPlan) -> ContentNeeds {
    let mut needs = ContentNeeds::default();
    let mut surface_m2 = 0.0;
    for w in &plan.furniture {
        let Some([x, y, z]) = typical(&w.noun) else {
            continue;
        };
        let n = f64::from(w.count);
        needs.floor_m2 += x * y * n;
        if !matches!(
            w.arrangement,
            Arrangement::Center | Arrangement::Around { .. } | Arrangement::Facing { .. }
        ) {
            needs.wall_m += (x + 0.1) * n;
        }
        // Shelves offer a surface per ~0.35 m of height; tables and cabinets their top.
        let levels = if w.noun.contains("shel") {
            (z / 0.35).floor().max(1.0)
        } else {
            1.0
        };
        surface_m2 += x * y * levels * n;
    }
    for w in &plan.wall {
        if let Some([x, ..]) = typical(&w.noun) {
            needs.wall_m += x * f64::from(w.count);
        }
    }
    let items_m2: f64 = plan
        .surfaces
        .iter()
        .flat_map(|s| &s.items)
        .filter_map(|w| typical(&w.noun).map(|[x, y, _]| x * y * f64::from(w.count) * 1.6))
        .sum();
    if items_m2 > surface_m2 {
        // Extra shelf units of 0.9 x 0.32 m with three levels.
        let per_shelf = 0.9 * 0.32 * 3.0;
        let extra = ((items_m2 - surface_m2) / per_shelf).ceil();
        needs.floor_m2 += extra * 0.9 * 0.32;
        needs.wall_m += extra;
    }
    needs
}

/// Grows `[long, short]` until it holds `needs`: floor area for the pieces plus circulation,
/// and perimeter for the pieces against walls plus a door.
pub fn fit_to_contents(size: [f64; 2], needs: &ContentNeeds) -> [f64; 2] {
    let [mut l, mut s] = size;
    let area_need = needs.floor_m2 * 2.8 + 2.0;
    if l * s < area_need {
        let k = (area_need / (l * s)).sqrt();
        l *= k;
        s *= k;
    }
    let usable = 2.0 * (l + s) - 2.2;
    let wall_need = needs.wall_m * 1.1;
    if usable < wall_need {
        let extra = (wall_need - usable) / 2.0;
        l += extra * 0.6;
        s += extra * 0.4;
    }
    if l / s > 2.0 {
        s = l / 2.0;
    }
    [round1(l.max(s)), round1(s.min(l))]
}

fn round1(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}

/// The furniture plan of a room prompt: the plan the placement stages build and the layout
/// sizes the room for. In a house the room is typed as the layout typed it. When
/// `room_prompt` is the brief's prompt of one of the house's rooms, the plan is that room's
/// in the reading of the whole house. Otherwise the room prompt is read alone, and when it
/// still names other rooms of the house ("the clinic comprises a waiting room, two treatment
/// rooms ..."), its contents are those the reader put in the room of that type.
///
/// `house` is the house's whole prompt (`None` for one room): what it counts exactly in
/// other rooms, or excludes anywhere, no default of this room adds
/// (`plan::plan_room_of_house`).
pub fn room_plan(room_type: &str, room_prompt: &str, house: Option<&str>) -> RoomPlan {
    let Some(house) = house else {
        return plan_house_room(&prompt::read(room_prompt), 0);
    };
    // One reader: a room of the house's brief is planned from the house's own reading, where
    // every sentence was read in its context ("A seaside bed and breakfast with three guest
    // rooms, each with a double bed" names no seaside bed in the guest room).
    let whole = prompt::read(house);
    let brief = super::brief::from_reading(house, &whole);
    if brief.rooms.len() == whole.rooms.len()
        && let Some(i) = (0..brief.rooms.len()).find(|&i| brief.room_prompt(i) == room_prompt)
    {
        let mut reading = whole;
        reading.rooms[i].room_type = room_type.to_string();
        return plan_room_of_house(&reading, i, &HouseContext::default());
    }
    let mut reading = prompt::read(room_prompt);
    reading.room_type = room_type.to_string();
    let i = reading
        .rooms
        .iter()
        .position(|r| r.room_type == room_type)
        .unwrap_or(0);
    if let Some(r) = reading.rooms.get_mut(i) {
        r.room_type = room_type.to_string();
    }
    let own: Vec<&str> = reading
        .mentions
        .iter()
        .filter(|m| m.room == i)
        .map(|m| m.category.as_str())
        .collect();
    let house = whole;
    let mut elsewhere: Vec<String> = house
        .mentions
        .iter()
        .filter(|m| !m.negated && matches!(m.count, prompt::Count::Exactly(_)))
        .map(|m| m.category.clone())
        .filter(|c| !own.contains(&c.as_str()))
        .collect();
    elsewhere.sort();
    elsewhere.dedup();
    let mut excluded: Vec<String> = house
        .mentions
        .iter()
        .filter(|m| m.negated)
        .flat_map(|m| [m.category.clone(), m.noun.clone()])
        .collect();
    excluded.sort();
    excluded.dedup();
    let context = HouseContext {
        elsewhere,
        excluded,
    };
    plan_room_of_house(&reading, i, &context)
}

/// Builds the house specification of a brief.
pub fn house_spec(brief: &HouseBrief) -> HouseSpec {
    let k = knowledge();
    let mut ids = IdAllocator::new();
    let mut rooms: Vec<RoomSpec> = Vec::new();
    for (i, r) in brief.rooms.iter().enumerate() {
        let kind = knowledge::kind(&r.room_type);
        let id = ids.allocate(&r.room_type);
        let scale = r.size_scale * brief.size_scale;
        let prompt_text = brief.room_prompt(i);
        let plan = room_plan(
            &r.room_type,
            &prompt_text,
            brief.is_house.then_some(brief.prompt.as_str()),
        );
        let base = kind.size.scaled(scale);
        let size = if kind.role == Role::Hub {
            [round1(base[0]), round1(base[1])]
        } else {
            fit_to_contents(base, &content_needs(&plan))
        };
        let wet = kind.role == Role::Wet;
        // A house-wide floor ("hardwood throughout") stays out of wet rooms unless it suits.
        let house_floor = brief
            .floor_material
            .clone()
            .filter(|m| !wet || k.house().wet_floor_materials.contains(m));
        rooms.push(RoomSpec {
            id,
            room_type: r.room_type.clone(),
            label: if r.ordinal[1] > 1 {
                format!("{} {}", r.label, r.ordinal[0])
            } else {
                r.label.clone()
            },
            role: kind.role,
            prompt: prompt_text,
            min_side: kind.min_side.min(size[1]),
            size,
            windows: kind.windows,
            sill: kind.sill,
            floor_material: r
                .floor_material
                .clone()
                .or(house_floor)
                .unwrap_or(kind.floor.clone()),
            wall_material: r
                .wall_material
                .clone()
                .or(brief.wall_material.clone().filter(|_| !wet))
                .unwrap_or(kind.wall.clone()),
            owner: None,
            parents: Vec::new(),
        });
    }
    for (i, r) in brief.rooms.iter().enumerate() {
        if let Some(o) = r.owner.and_then(|o| rooms.get(o)).map(|o| o.id.clone()) {
            rooms[i].owner = Some(o);
        }
    }
    let mut adjacency = Vec::new();
    for &(a, b) in &brief.open_pairs {
        if let (Some(a), Some(b)) = (rooms.get(a), rooms.get(b)) {
            adjacency.push(Adjacency {
                a: a.id.clone(),
                b: b.id.clone(),
                link: Link::Open,
            });
        }
    }
    let wall_height = brief.wall_height.unwrap_or_else(|| {
        if rooms
            .iter()
            .any(|r| r.area() >= 30.0 && r.role != Role::Hub)
        {
            TALL_WALL_HEIGHT
        } else {
            WALL_HEIGHT
        }
    });
    let mut spec = HouseSpec {
        rooms,
        adjacency,
        wall_height,
        entrance: String::new(),
    };
    connect(&mut spec);
    spec
}

/// Decides the entrance, every room's parents (rooms it may be entered from) and the rule
/// adjacencies; grows the hub for the rooms that open onto it.
pub fn connect(spec: &mut HouseSpec) {
    let k = knowledge();
    let area = |r: &RoomSpec| r.area();
    let by_role = |spec: &HouseSpec, roles: &[Role]| -> Vec<String> {
        let mut v: Vec<&RoomSpec> = spec
            .rooms
            .iter()
            .filter(|r| roles.contains(&r.role))
            .collect();
        v.sort_by(|a, b| area(b).total_cmp(&area(a)));
        v.into_iter().map(|r| r.id.clone()).collect()
    };
    let hub = spec.hub().map(|r| r.id.clone());
    let entries = by_role(spec, &[Role::Entry]);
    let publics = by_role(spec, &[Role::Public]);
    let hubs = by_role(spec, &[Role::Hub]);
    // The entrance: reception or lobby, else the hallway, else the room type people come in
    // through (living room, restaurant, ...), else the largest passable room, else the
    // largest room.
    let living = k.house().entrance_preference.iter().find_map(|t| {
        spec.rooms
            .iter()
            .filter(|r| &r.room_type == t)
            .max_by(|a, b| area(a).total_cmp(&area(b)))
            .map(|r| r.id.clone())
    });
    spec.entrance = entries
        .first()
        .or(hubs.first())
        .or(living.as_ref())
        .or(publics.first())
        .cloned()
        .or_else(|| {
            by_role(spec, &[Role::Private, Role::Wet, Role::Service])
                .first()
                .cloned()
        })
        .unwrap_or_default();

    // Rule adjacencies (kitchen next to the dining room, ...).
    let mut rule_pairs: Vec<Adjacency> = Vec::new();
    for (rule_type, rule) in k.adjacency() {
        for a in spec.rooms.iter().filter(|r| r.room_type == rule_type) {
            let target = rule.next_to.iter().find_map(|t| {
                spec.rooms
                    .iter()
                    .find(|r| &r.room_type == t && r.id != a.id)
                    .map(|r| r.id.clone())
            });
            if let Some(b) = target
                && spec.pair(&a.id, &b).is_none()
                && !rule_pairs.iter().any(|p| p.joins(&a.id, &b))
            {
                rule_pairs.push(Adjacency {
                    a: a.id.clone(),
                    b,
                    link: if rule.required {
                        Link::Door
                    } else {
                        Link::Preferred
                    },
                });
            }
        }
    }
    spec.adjacency.extend(rule_pairs);

    let passable: Vec<String> = entries
        .iter()
        .chain(&publics)
        .chain(&hubs)
        .cloned()
        .collect();
    let ids: Vec<String> = spec.rooms.iter().map(|r| r.id.clone()).collect();
    for id in ids {
        let Some(r) = spec.room(&id).cloned() else {
            continue;
        };
        let required: Vec<String> = spec
            .adjacency
            .iter()
            .filter(|p| p.required() && (p.a == id))
            .map(|p| p.b.clone())
            .collect();
        let mut parents: Vec<String> = if let Some(o) = &r.owner {
            vec![o.clone()]
        } else if !required.is_empty() && r.role != Role::Hub && r.role != Role::Entry {
            required
        } else {
            match (&hub, r.role) {
                (_, Role::Hub) if Some(&id) == hub.as_ref() => Vec::new(),
                (Some(h), Role::Private | Role::Wet | Role::Service | Role::Entry | Role::Hub) => {
                    vec![h.clone()]
                }
                (Some(h), Role::Public) => {
                    let mut v = vec![h.clone()];
                    v.extend(passable.iter().filter(|p| **p != id && *p != h).cloned());
                    v
                }
                (None, _) => passable.iter().filter(|p| **p != id).cloned().collect(),
            }
        };
        parents.retain(|p| *p != id);
        if id == spec.entrance && hub.is_none() {
            parents.clear();
        }
        if let Some(r) = spec.rooms.iter_mut().find(|r| r.id == id) {
            r.parents = parents;
        }
    }

    // The hub must be long enough for the rooms that open onto it (on both sides).
    if let Some(h) = hub {
        let attached: f64 = spec
            .rooms
            .iter()
            .filter(|r| r.parents.first() == Some(&h))
            .map(|r| r.size[1] + 0.15)
            .sum();
        if let Some(hr) = spec.rooms.iter_mut().find(|r| r.id == h) {
            let want = (attached / 2.0 + 0.5).clamp(hr.size[0], 30.0);
            hr.size[0] = round1(want);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::brief;

    #[test]
    fn content_sizes_rooms_for_what_they_hold() {
        let bare = house_spec(&brief::read("A closet."));
        let full = house_spec(&brief::read(
            "A closet with twelve shelves along the walls.",
        ));
        let (a, b) = (&bare.rooms[0], &full.rooms[0]);
        assert!(b.area() > a.area(), "{:?} vs {:?}", b.size, a.size);
        // Twelve shelf units stand along the walls, with a door left over.
        assert!(
            2.0 * (b.size[0] + b.size[1]) - 2.2 >= 12.0 * 1.0,
            "{:?}",
            b.size
        );
        // Small objects that overflow the planned shelves (a pantry's knowledge brings three
        // shelf units) ask for more shelving.
        let one = content_needs(&room_plan("pantry", "A pantry with a cabinet.", None));
        let many = content_needs(&room_plan(
            "pantry",
            "A pantry with a cabinet holding 100 mugs and 100 bowls.",
            None,
        ));
        assert!(many.wall_m > one.wall_m + 0.9, "{one:?} {many:?}");
        // The pottery store of the issue is no 3 x 3 m box.
        let store = house_spec(&brief::read(
            "A pottery store with shelves along the walls. The shelves hold at least 30 cups and 30 bowls. There is a table with a large painted bowl.",
        ));
        assert!(store.rooms[0].size[1] > 3.0 && store.rooms[0].area() > 12.0);
    }

    /// The plans of every room of a house prompt, as the pipeline makes them.
    fn house_plans(prompt: &str) -> Vec<RoomPlan> {
        let b = brief::read(prompt);
        (0..b.rooms.len())
            .map(|i| room_plan(&b.rooms[i].room_type, &b.room_prompt(i), Some(&b.prompt)))
            .collect()
    }

    #[test]
    fn a_house_room_is_planned_from_the_house_reading() {
        // Read alone, the guest room's text ("A seaside bed and breakfast with three guest
        // rooms, each with a double bed") would name a seaside bed.
        let plans = house_plans(
            "A seaside bed and breakfast with three guest rooms, each with a double bed and a \
             wicker armchair. Downstairs, the breakfast room has four small tables.",
        );
        let guest: Vec<&RoomPlan> = plans
            .iter()
            .filter(|p| p.room_type == "guest_bedroom" || p.room_type == "bedroom")
            .collect();
        assert_eq!(
            guest.len(),
            3,
            "{:?}",
            plans.iter().map(|p| &p.room_type).collect::<Vec<_>>()
        );
        for p in guest {
            let beds: u32 = p
                .furniture
                .iter()
                .filter(|w| w.noun == "bed")
                .map(|w| w.count)
                .sum();
            assert_eq!(beds, 1, "{:?}", p.furniture);
            assert!(
                p.all_wants().all(|w| !w.description.contains("seaside")),
                "{:?}",
                p.furniture
            );
        }
    }

    #[test]
    fn what_a_house_counts_in_one_room_no_other_room_adds() {
        // The house's one armchair and two bookshelves are the ones the prompt placed; the
        // living room keeps its sofa (the piece that makes it) and the playroom its toy box.
        let plans = house_plans(
            "A family home with a living room, a playroom, a master bedroom and two children's \
             bedrooms. The living room has a sectional sofa. The master bedroom has a king bed, \
             two reading lamps and a rattan armchair. Each children's bedroom has a bunk bed, a \
             desk and a bookshelf.",
        );
        let count = |noun: &str| -> u32 {
            plans
                .iter()
                .flat_map(|p| p.furniture.iter())
                .filter(|w| w.noun == noun)
                .map(|w| w.count)
                .sum()
        };
        assert_eq!(count("armchair"), 1);
        assert_eq!(count("bookshelf"), 2);
        assert_eq!(count("desk"), 2, "reading lamps stand on the nightstands");
        let living = plans.iter().find(|p| p.room_type == "living_room");
        assert!(living.is_some_and(|p| p.furniture.iter().any(|w| w.noun.ends_with("sofa"))));
    }

    #[test]
    fn what_a_house_excludes_no_room_adds() {
        // The negation names the kind ("lamps"): table and floor lamps alike. A ceiling light is
        // no lamp (WordNet files chandeliers and ceiling fixtures under lighting fixtures).
        let plans = house_plans(
            "A tiny two-room cottage: a kitchen with a wood stove, a table and two stools, and \
             a bedroom with a brass bed. There are no lamps, only candles. There are no rugs \
             anywhere in the cottage.",
        );
        for p in &plans {
            for w in p.all_wants() {
                assert!(
                    !w.noun.contains("lamp") && w.noun != "rug",
                    "{}: {}",
                    p.room_type,
                    w.noun
                );
            }
        }
    }

    #[test]
    fn en_suites_hubs_and_entrances() {
        let spec = house_spec(&brief::read(
            "A boutique hotel with a reception, four guest bedrooms with en-suite bathrooms, a restaurant, a kitchen, a gym, a lounge, and a corridor.",
        ));
        assert_eq!(spec.entrance, "reception_0");
        let corridor = spec.room("corridor_0").unwrap();
        assert!(corridor.size[0] > 6.0, "{:?}", corridor.size);
        for r in spec.rooms.iter().filter(|r| r.room_type == "en_suite") {
            assert_eq!(r.parents, vec![r.owner.clone().unwrap()]);
            assert_eq!(r.floor_material, "tile");
        }
        let bed = spec.room("guest_bedroom_2").unwrap();
        assert_eq!(bed.parents, vec!["corridor_0".to_string()]);
        let kitchen = spec.room("kitchen_0").unwrap();
        assert_eq!(kitchen.parents, vec!["restaurant_0".to_string()]);
    }
}
