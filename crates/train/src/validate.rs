//! A gearing file's checks: every gear, arbor, mesh and pointer named once and consistent, no loop
//! of meshes, the pin-and-slot and the cosmos display's devices sound, and the trains found.

use super::*;

impl Gearing {
    pub(super) fn validate(&self, errors: &Errors<'_>) -> Result<(), GearingError> {
        self.named(errors)?;
        // Every experiment runs the gearing's meshes: none would give empty tables that look
        // like results.
        if self.meshes.is_empty() {
            return Err(errors.at(
                "meshes",
                format_args!(
                    "must list at least one mesh: every experiment runs a gearing's meshes, and this one has {} gears and no meshes",
                    self.gears.len()
                ),
            ));
        }
        let names = self.validate_gears(errors)?;
        let (arbor_names, arbor_of) = self.validate_arbors(errors, &names)?;
        self.validate_meshes(errors, &names, &arbor_of)?;
        self.no_loop_of_meshes(errors, &arbor_of)?;
        self.validate_pointers(errors, &arbor_names, &arbor_of)
    }

    /// Every gear's name once, its teeth and its measured radius within limits; the names.
    pub(super) fn validate_gears(
        &self,
        errors: &Errors<'_>,
    ) -> Result<BTreeSet<&str>, GearingError> {
        // Gears.
        let mut names = BTreeSet::new();
        for gear in &self.gears {
            let at = format!("gear {}", gear.name);
            if !names.insert(gear.name.as_str()) {
                return Err(errors.at(at, "duplicate gear name"));
            }
            if gear.teeth < 3 {
                return Err(errors.at(
                    at,
                    format_args!("teeth must be at least 3, got {}", gear.teeth),
                ));
            }
            if gear.teeth > MAX_TEETH {
                return Err(errors.at(
                    at,
                    format_args!(
                        "teeth must be at most {MAX_TEETH} (the limit on teeth), got {}",
                        gear.teeth
                    ),
                ));
            }
            if let Some(a) = gear.measured_radius
                && !(a.is_finite() && a > 0.0 && a <= MAX_SIZE_MM)
            {
                return Err(errors.at(
                    at,
                    format_args!(
                        "measured_radius must be above 0 and at most {} mm (10 m: larger is no gear of a mechanism), got {}",
                        fmt_number(MAX_SIZE_MM),
                        fmt_number(a)
                    ),
                ));
            }
            Self::check_design_radius(gear).map_err(|rule| errors.at(&at, rule))?;
        }
        Ok(names)
    }

    /// Every arbor's name once, each holding known gears, each gear on exactly one arbor; the
    /// arbors' names and the arbor of each gear.
    pub(super) fn validate_arbors<'a>(
        &'a self,
        errors: &Errors<'_>,
        names: &BTreeSet<&str>,
    ) -> Result<(BTreeSet<&'a str>, BTreeMap<&'a str, &'a str>), GearingError> {
        // Arbors: each gear on exactly one.
        let mut arbor_names = BTreeSet::new();
        let mut arbor_of: BTreeMap<&str, &str> = BTreeMap::new();
        for arbor in &self.arbors {
            let at = format!("arbor {}", arbor.name);
            if !arbor_names.insert(arbor.name.as_str()) {
                return Err(errors.at(at, "duplicate arbor name"));
            }
            if arbor.gears.is_empty() {
                return Err(errors.at(at, "has no gears"));
            }
            for g in &arbor.gears {
                if !names.contains(g.as_str()) {
                    return Err(errors.at(at, format_args!("unknown gear {g}")));
                }
                if let Some(other) = arbor_of.insert(g, &arbor.name) {
                    return Err(errors.at(
                        format_args!("gear {g}"),
                        format_args!("on two arbors: {other} and {}", arbor.name),
                    ));
                }
            }
        }
        for gear in &self.gears {
            if !arbor_of.contains_key(gear.name.as_str()) {
                return Err(errors.at(format_args!("gear {}", gear.name), "on no arbor"));
            }
        }
        Ok((arbor_names, arbor_of))
    }

    /// Every mesh's label once, between known gears on two arbors.
    pub(super) fn validate_meshes(
        &self,
        errors: &Errors<'_>,
        names: &BTreeSet<&str>,
        arbor_of: &BTreeMap<&str, &str>,
    ) -> Result<(), GearingError> {
        // Meshes.
        let mut labels = BTreeSet::new();
        for mesh in &self.meshes {
            let at = format!("mesh {}", mesh.label);
            if !labels.insert(mesh.label.as_str()) {
                return Err(errors.at(at, "duplicate mesh label"));
            }
            for g in [&mesh.driver, &mesh.driven] {
                if !names.contains(g.as_str()) {
                    return Err(errors.at(at, format_args!("unknown gear {g}")));
                }
            }
            let a1 = arbor_of[mesh.driver.as_str()];
            let a2 = arbor_of[mesh.driven.as_str()];
            if a1 == a2 {
                return Err(errors.at(
                    at,
                    format_args!(
                        "driver {} and driven {} are both on arbor {a1}",
                        mesh.driver, mesh.driven
                    ),
                ));
            }
        }
        Ok(())
    }

    /// No loop of meshes: joined through meshes, the arbors form a forest.
    pub(super) fn no_loop_of_meshes(
        &self,
        errors: &Errors<'_>,
        arbor_of: &BTreeMap<&str, &str>,
    ) -> Result<(), GearingError> {
        // No loop of meshes: joined through meshes, the arbors form a forest.
        let arbor_index: BTreeMap<&str, usize> = self
            .arbors
            .iter()
            .enumerate()
            .map(|(i, a)| (a.name.as_str(), i))
            .collect();
        let mut parent: Vec<usize> = (0..self.arbors.len()).collect();
        for mesh in &self.meshes {
            let (a1, a2) = (
                arbor_of[mesh.driver.as_str()],
                arbor_of[mesh.driven.as_str()],
            );
            let r1 = find(&mut parent, arbor_index[a1]);
            let r2 = find(&mut parent, arbor_index[a2]);
            if r1 == r2 {
                return Err(errors.at(
                    format_args!("mesh {}", mesh.label),
                    format_args!(
                        "closes a loop of meshes: arbors {a1} and {a2} are already joined through other meshes (each arbor must be turned along one chain of meshes)"
                    ),
                ));
            }
            parent[r1.max(r2)] = r1.min(r2);
        }
        Ok(())
    }

    /// Every pointer's name once, from a known input arbor along a connected chain of known
    /// meshes.
    pub(super) fn validate_pointers(
        &self,
        errors: &Errors<'_>,
        arbor_names: &BTreeSet<&str>,
        arbor_of: &BTreeMap<&str, &str>,
    ) -> Result<(), GearingError> {
        // Pointers: known input, known meshes, a connected chain.
        let mut pointer_names = BTreeSet::new();
        for pointer in &self.pointers {
            let at = format!("pointer {}", pointer.name);
            if !pointer_names.insert(pointer.name.as_str()) {
                return Err(errors.at(at, "duplicate pointer name"));
            }
            if !arbor_names.contains(pointer.input.as_str()) {
                return Err(errors.at(at, format_args!("unknown input arbor {}", pointer.input)));
            }
            if pointer.meshes.is_empty() {
                return Err(errors.at(at, "has no meshes"));
            }
            let mut current = pointer.input.as_str();
            let mut previous: Option<&str> = None;
            for label in &pointer.meshes {
                let Some(mesh) = self.mesh(label) else {
                    return Err(errors.at(at, format_args!("unknown mesh {label}")));
                };
                let driver_arbor = arbor_of[mesh.driver.as_str()];
                if driver_arbor != current {
                    let want = match previous {
                        None => format!("the input arbor {current}"),
                        Some(p) => format!("arbor {current} (driven by mesh {p})"),
                    };
                    return Err(errors.at(
                        at,
                        format_args!(
                            "chain does not connect at mesh {label}: its driver {} is on arbor {driver_arbor}, not on {want}",
                            mesh.driver
                        ),
                    ));
                }
                current = arbor_of[mesh.driven.as_str()];
                previous = Some(label);
            }
        }
        Ok(())
    }

    /// The rules of a gear's `design_radius`: a positive finite size, never beside a measured
    /// radius, and a pitch radius (so only with [`Sizing::Pitch`]).
    pub(super) fn check_design_radius(gear: &GearData) -> Result<(), String> {
        let Some(d) = gear.design_radius else {
            return Ok(());
        };
        if !(d.is_finite() && d > 0.0 && d <= MAX_SIZE_MM) {
            return Err(format!(
                "design_radius must be above 0 and at most {} mm, got {}",
                fmt_number(MAX_SIZE_MM),
                fmt_number(d)
            ));
        }
        if gear.measured_radius.is_some() {
            return Err(
                "has both measured_radius and design_radius: a radius is measured or designed, give one"
                    .into(),
            );
        }
        if gear.sizing != Sizing::Pitch {
            return Err("design_radius is a pitch radius: the gear needs `sizing: Pitch`".into());
        }
        Ok(())
    }

    /// Every gear, arbor, mesh and pointer has a name that is not blank: messages name items by
    /// it ("gear : teeth must be at least 3" says nothing), and so do the settings that pick one.
    /// Refused naming the list and the item's place in it.
    pub(super) fn named(&self, errors: &Errors<'_>) -> Result<(), GearingError> {
        let lists: [(&str, &str, Vec<&str>); 4] = [
            (
                "gears",
                "name",
                self.gears.iter().map(|g| g.name.as_str()).collect(),
            ),
            (
                "arbors",
                "name",
                self.arbors.iter().map(|a| a.name.as_str()).collect(),
            ),
            (
                "meshes",
                "label",
                self.meshes.iter().map(|m| m.label.as_str()).collect(),
            ),
            (
                "pointers",
                "name",
                self.pointers.iter().map(|p| p.name.as_str()).collect(),
            ),
        ];
        for (list, field, names) in lists {
            if let Some(i) = names.iter().position(|n| n.trim().is_empty()) {
                return Err(errors.at(
                    format_args!("{list}[{i}]"),
                    format_args!(
                        "{field} must not be empty (got {:?}): items are named in messages and settings",
                        names[i]
                    ),
                ));
            }
            // A name is printed in tables, data files and on the terminal: a control character
            // (a NUL, a line break, an escape that recolours the terminal) would break a line
            // or hide text.
            if let Some(i) = names.iter().position(|n| n.chars().any(char::is_control)) {
                return Err(errors.at(
                    format_args!("{list}[{i}]"),
                    format_args!(
                        "{field} {:?} must not contain a control character (a line break, a tab, a NUL, an escape): names are printed in tables, data files and on the terminal",
                        names[i]
                    ),
                ));
            }
        }
        // A per-mesh table names its cells CASE/MESH (`cargo xtask replay table3 B/m3-e3`).
        if let Some(i) = self.meshes.iter().position(|m| m.label.contains('/')) {
            return Err(errors.at(
                format_args!("meshes[{i}]"),
                format_args!(
                    "label `{}` must not contain `/`: the cells of a per-mesh table are named CASE/MESH (cargo xtask replay table3 B/m3-e3), so its cells could not be replayed; write e.g. `m3-e3`",
                    self.meshes[i].label
                ),
            ));
        }
        Ok(())
    }

    /// The rules of the optional `pin_and_slot` section (after [`Gearing::validate`]).
    pub(super) fn validate_pin_and_slot(&self, errors: &Errors<'_>) -> Result<(), GearingError> {
        let Some(ps) = &self.pin_and_slot else {
            return Ok(());
        };
        let at = |field: &str| format!("pin_and_slot.{field}");
        for (field, name) in [
            ("pin_gear", &ps.pin_gear),
            ("slot_gear", &ps.slot_gear),
            ("turntable", &ps.turntable),
        ] {
            if self.gear(name).is_none() {
                return Err(errors.at(at(field), format_args!("unknown gear {name}")));
            }
        }
        if ps.pin_gear == ps.slot_gear {
            return Err(errors.at(
                at("slot_gear"),
                format_args!("must differ from the pin gear {}", ps.pin_gear),
            ));
        }
        let (Some(pin_arbor), Some(slot_arbor), Some(turntable_arbor)) = (
            self.arbor_of(&ps.pin_gear),
            self.arbor_of(&ps.slot_gear),
            self.arbor_of(&ps.turntable),
        ) else {
            return Err(errors.at(at("pin_gear"), "a gear is on no arbor"));
        };
        if pin_arbor != slot_arbor {
            return Err(errors.at(
                at("slot_gear"),
                format_args!(
                    "{} is on arbor {slot_arbor}, not on the pin gear's arbor {pin_arbor} (the rigid coupling the pin-and-slot replaces)",
                    ps.slot_gear
                ),
            ));
        }
        if turntable_arbor == pin_arbor {
            return Err(errors.at(
                at("turntable"),
                format_args!(
                    "{} is on arbor {pin_arbor}, the arbor of the pin and slot gears; the turntable must be another arbor",
                    ps.turntable
                ),
            ));
        }
        for (field, v) in [
            ("axis_offset", ps.axis_offset),
            ("pin_radius", ps.pin_radius),
        ] {
            if !(v.is_finite() && v > 0.0 && v <= MAX_SIZE_MM) {
                return Err(errors.at(
                    at(field),
                    format_args!(
                        "must be above 0 and at most {} mm (10 m: larger is no part of a mechanism), got {}",
                        fmt_number(MAX_SIZE_MM),
                        fmt_number(v)
                    ),
                ));
            }
        }
        if ps.axis_offset >= ps.pin_radius {
            return Err(errors.at(
                at("axis_offset"),
                format_args!(
                    "must be less than the pin radius {} mm (the pin must stay in the slot), got {}",
                    fmt_number(ps.pin_radius),
                    fmt_number(ps.axis_offset)
                ),
            ));
        }
        self.pin_and_slot_trains(errors, ps, pin_arbor, turntable_arbor)
    }

    /// Every pointer's train through the pin's arbor enters it by the pin gear and leaves it by
    /// the slot gear, and turns the turntable from its input; at least one runs through it.
    pub(super) fn pin_and_slot_trains(
        &self,
        errors: &Errors<'_>,
        ps: &PinAndSlot,
        pin_arbor: &str,
        turntable_arbor: &str,
    ) -> Result<(), GearingError> {
        let at = |field: &str| format!("pin_and_slot.{field}");
        let mut through = 0;
        for pointer in &self.pointers {
            let Some(i) = pointer.meshes.iter().position(|label| {
                self.mesh(label)
                    .and_then(|m| self.arbor_of(&m.driven))
                    .is_some_and(|a| a == pin_arbor)
            }) else {
                continue;
            };
            through += 1;
            let entering = self.mesh(&pointer.meshes[i]).map(|m| m.driven.as_str());
            if entering != Some(ps.pin_gear.as_str()) {
                return Err(errors.at(
                    at("pin_gear"),
                    format_args!(
                        "pointer {}'s train enters arbor {pin_arbor} through mesh {}, which does not drive the pin gear {}",
                        pointer.name, pointer.meshes[i], ps.pin_gear
                    ),
                ));
            }
            let leaving = pointer
                .meshes
                .get(i + 1)
                .and_then(|label| self.mesh(label))
                .map(|m| m.driver.as_str());
            if leaving != Some(ps.slot_gear.as_str()) {
                return Err(errors.at(
                    at("slot_gear"),
                    format_args!(
                        "pointer {}'s train does not leave arbor {pin_arbor} through a mesh driven by the slot gear {}",
                        pointer.name, ps.slot_gear
                    ),
                ));
            }
            if self.mesh_path(&pointer.input, turntable_arbor).is_none() {
                return Err(errors.at(
                    at("turntable"),
                    format_args!(
                        "no chain of meshes turns the turntable arbor {turntable_arbor} from pointer {}'s input arbor {}",
                        pointer.name, pointer.input
                    ),
                ));
            }
        }
        if through == 0 {
            return Err(errors.at(
                at("pin_gear"),
                format_args!(
                    "no pointer's train runs through the pin gear {}",
                    ps.pin_gear
                ),
            ));
        }
        Ok(())
    }

    /// The rules of the cosmos's sections (after [`Gearing::validate`]): the epicyclic system,
    /// the pin-and-slot devices, the differentials, and each mesh's stated margin.
    pub(super) fn validate_cosmos(&self, errors: &Errors<'_>) -> Result<(), GearingError> {
        for m in &self.meshes {
            if let Some(margin) = m.margin
                && !(margin.is_finite() && (0.0..=MAX_SIZE_MM).contains(&margin))
            {
                return Err(errors.at(
                    format_args!("mesh {}", m.label),
                    format_args!(
                        "margin must be at least 0 and at most {} mm, got {}",
                        fmt_number(MAX_SIZE_MM),
                        fmt_number(margin)
                    ),
                ));
            }
        }
        self.validate_epicyclic(errors)?;
        for (i, d) in self.devices.iter().enumerate() {
            self.validate_device(d)
                .map_err(|(field, rule)| errors.at(format_args!("devices[{i}].{field}"), rule))?;
        }
        let mut names = BTreeSet::new();
        for (i, d) in self.differentials.iter().enumerate() {
            let at = |field: &str| format!("differentials[{i}].{field}");
            if d.name.trim().is_empty() || !names.insert(d.name.as_str()) {
                return Err(errors.at(at("name"), "must be a name not empty and not used twice"));
            }
            for (field, arbor) in [("input", &d.input), ("plus", &d.plus), ("minus", &d.minus)] {
                if self.arbor(arbor).is_none() {
                    return Err(errors.at(at(field), format_args!("unknown arbor {arbor}")));
                }
            }
            for (field, teeth) in [
                ("driver_teeth", d.driver_teeth),
                ("driven_teeth", d.driven_teeth),
            ] {
                if !(3..=MAX_TEETH).contains(&teeth) {
                    return Err(errors.at(
                        at(field),
                        format_args!("must be at least 3 and at most {MAX_TEETH}, got {teeth}"),
                    ));
                }
            }
            if self.differential_rate(&d.name).is_none() {
                return Err(errors.at(
                    at("plus"),
                    format_args!(
                        "no chain of meshes gives the rates of {} and {} from {}",
                        d.plus, d.minus, d.input
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The rules of the `epicyclic` section: known and distinct arbors, every mesh within the
    /// system or outside it, every listed arbor turned from the fixed one, every pointer into
    /// the system entering by the fixed arbor.
    pub(super) fn validate_epicyclic(&self, errors: &Errors<'_>) -> Result<(), GearingError> {
        let Some(e) = &self.epicyclic else {
            return Ok(());
        };
        let at = |field: &str| format!("epicyclic.{field}");
        for (field, arbor) in [("carrier", &e.carrier), ("fixed", &e.fixed)] {
            if self.arbor(arbor).is_none() {
                return Err(errors.at(at(field), format_args!("unknown arbor {arbor}")));
            }
        }
        if e.carrier == e.fixed {
            return Err(errors.at(
                at("fixed"),
                "must differ from the carrier: the fixed gears stay still while the carrier turns",
            ));
        }
        let mut seen = BTreeSet::new();
        for a in &e.arbors {
            if self.arbor(a).is_none() {
                return Err(errors.at(at("arbors"), format_args!("unknown arbor {a}")));
            }
            if a == &e.carrier || a == &e.fixed || !seen.insert(a.as_str()) {
                return Err(errors.at(
                    at("arbors"),
                    format_args!("arbor {a} is listed twice, or is the carrier or the fixed arbor"),
                ));
            }
            if self.mesh_path(&e.fixed, a).is_none() {
                return Err(errors.at(
                    at("arbors"),
                    format_args!(
                        "no chain of meshes turns arbor {a} from the fixed arbor {}",
                        e.fixed
                    ),
                ));
            }
        }
        for m in &self.meshes {
            let (a1, a2) = (self.arbor_of(&m.driver), self.arbor_of(&m.driven));
            let (i1, i2) = (
                a1.is_some_and(|a| self.in_epicyclic(a)),
                a2.is_some_and(|a| self.in_epicyclic(a)),
            );
            if i1 != i2 {
                return Err(errors.at(
                    format_args!("mesh {}", m.label),
                    "joins an arbor of the epicyclic system to one outside it: a mesh runs in one frame (list both arbors in epicyclic.arbors, or neither)",
                ));
            }
        }
        for p in &self.pointers {
            if p.input != e.fixed && self.in_epicyclic(&p.input) {
                return Err(errors.at(
                    format_args!("pointer {}", p.name),
                    format_args!(
                        "its input {} is a carried arbor: a train in the carrier's frame starts at the fixed arbor {}",
                        p.input, e.fixed
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The rules of one pin-and-slot device, as (field, rule) when broken: a pointer run in the
    /// carrier's frame, one device per pointer, the pin gear where its kind needs it, and a pin
    /// radius on the right side of the offset.
    pub(super) fn validate_device(&self, d: &PinDevice) -> Result<(), (&'static str, String)> {
        let Some(p) = self.pointer(&d.pointer) else {
            return Err(("pointer", format!("unknown pointer {}", d.pointer)));
        };
        if !self.is_epicyclic_pointer(&p.name) {
            return Err((
                "pointer",
                format!(
                    "pointer {} is not run in a carrier's frame (its input is not an epicyclic section's fixed arbor)",
                    p.name
                ),
            ));
        }
        if self
            .devices
            .iter()
            .filter(|x| x.pointer == d.pointer)
            .count()
            > 1
        {
            return Err(("pointer", format!("pointer {} has two devices", p.name)));
        }
        for (field, v) in [("axis_offset", d.axis_offset), ("pin_radius", d.pin_radius)] {
            if !(v.is_finite() && v > 0.0 && v <= MAX_SIZE_MM) {
                return Err((
                    field,
                    format!(
                        "must be above 0 and at most {} mm, got {}",
                        fmt_number(MAX_SIZE_MM),
                        fmt_number(v)
                    ),
                ));
            }
        }
        let driven = |i: usize| self.mesh(&p.meshes[i]).map(|m| m.driven.as_str());
        let driver = |i: usize| {
            p.meshes
                .get(i)
                .and_then(|l| self.mesh(l))
                .map(|m| m.driver.as_str())
        };
        match d.kind {
            DeviceKind::Follower => {
                if d.slot_gear.is_some() {
                    return Err(("slot_gear", "a follower has no slot gear".into()));
                }
                if driven(p.meshes.len() - 1) != Some(d.pin_gear.as_str()) {
                    return Err((
                        "pin_gear",
                        format!(
                            "{} is not the gear pointer {}'s last mesh drives (the follower is the pointer)",
                            d.pin_gear, p.name
                        ),
                    ));
                }
                if d.pin_radius >= d.axis_offset {
                    return Err((
                        "pin_radius",
                        format!(
                            "must be less than the axis offset {} mm (the pin stays off the follower's axis), got {}",
                            fmt_number(d.axis_offset),
                            fmt_number(d.pin_radius)
                        ),
                    ));
                }
            }
            DeviceKind::SlotGear => {
                let Some(slot) = &d.slot_gear else {
                    return Err(("slot_gear", "a slot-gear device names its slot gear".into()));
                };
                let stage = (0..p.meshes.len()).find(|&i| driven(i) == Some(d.pin_gear.as_str()));
                let ok = stage.is_some_and(|i| driver(i + 1) == Some(slot.as_str()))
                    && slot != &d.pin_gear
                    && self.arbor_of(slot) == self.arbor_of(&d.pin_gear);
                if !ok {
                    return Err((
                        "slot_gear",
                        format!(
                            "pointer {}'s train must drive the pin gear {} and go on from the slot gear {}, on the pin gear's arbor",
                            p.name, d.pin_gear, slot
                        ),
                    ));
                }
                if d.axis_offset >= d.pin_radius {
                    return Err((
                        "axis_offset",
                        format!(
                            "must be less than the pin radius {} mm (the pin must stay in the slot), got {}",
                            fmt_number(d.pin_radius),
                            fmt_number(d.axis_offset)
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Groups the gears into mesh-connected components and fits one `mu` to each.
    pub(super) fn find_components(
        &self,
        errors: &Errors<'_>,
    ) -> Result<Vec<Component>, GearingError> {
        let index: BTreeMap<&str, usize> = self
            .gears
            .iter()
            .enumerate()
            .map(|(i, g)| (g.name.as_str(), i))
            .collect();
        let mut parent: Vec<usize> = (0..self.gears.len()).collect();
        for mesh in &self.meshes {
            let a = find(&mut parent, index[mesh.driver.as_str()]);
            let b = find(&mut parent, index[mesh.driven.as_str()]);
            parent[a.max(b)] = a.min(b);
        }
        // Roots in file order of their first gear.
        let mut by_root: BTreeMap<usize, Component> = BTreeMap::new();
        for (i, gear) in self.gears.iter().enumerate() {
            let root = find(&mut parent, i);
            by_root
                .entry(root)
                .or_insert_with(|| Component {
                    gears: Vec::new(),
                    meshes: Vec::new(),
                    mu: 0.0,
                })
                .gears
                .push(gear.name.clone());
        }
        for mesh in &self.meshes {
            let root = find(&mut parent, index[mesh.driver.as_str()]);
            if let Some(c) = by_root.get_mut(&root) {
                c.meshes.push(mesh.label.clone());
            }
        }
        let mut components: Vec<Component> = by_root.into_values().collect();
        for c in &mut components {
            let (mut na, mut nn) = (0.0_f64, 0.0_f64);
            let first = &self.gears[index[c.gears[0].as_str()]];
            for name in &c.gears {
                let gear = &self.gears[index[name.as_str()]];
                if gear.sizing != first.sizing {
                    return Err(errors.at(
                        format_args!("gear {name}"),
                        format_args!(
                            "sizing {:?} differs from gear {}'s {:?} in the same group of meshed gears (one rule sizes a group)",
                            gear.sizing, first.name, first.sizing
                        ),
                    ));
                }
                if let Some(a) = gear.measured_radius.or(gear.design_radius) {
                    let n = f64::from(gear.teeth);
                    na += n * a;
                    nn += n * n;
                }
            }
            if nn == 0.0 {
                let gears = c.gears.join(", ");
                return Err(match c.meshes.first() {
                    Some(label) => errors.at(
                        format_args!("mesh {label}"),
                        format_args!(
                            "no gear of its mesh component ({gears}) has a measured or design radius; it cannot be sized"
                        ),
                    ),
                    None => errors.at(
                        format_args!("gear {gears}"),
                        "no measured radius and no mesh partner; it cannot be sized",
                    ),
                });
            }
            c.mu = na / nn;
            // Radii near the ends of the float range overflow to infinity or round to zero.
            for name in &c.gears {
                let gear = &self.gears[index[name.as_str()]];
                let tip = c.mu * f64::from(gear.teeth);
                if !(tip.is_finite() && tip > 0.0) {
                    return Err(errors.at(
                        format_args!("gear {name}"),
                        format_args!(
                            "its tip radius, sized from the measured radii of its mesh component, is {tip} mm; measured radii must give a positive finite size"
                        ),
                    ));
                }
            }
        }
        Ok(components)
    }
}
