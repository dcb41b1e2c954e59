//! Scenario texts that several test files build on: the quarter car as a generic `mdof` model
//! ([`quarter_car_scenario`]) and a body in bounce and roll on two wheels ([`two_wheels`]).

/// The quarter car as a generic `mdof` model: body 300 kg, wheel 40 kg, suspension 20 kN/m and 1.5 kN s/m
/// between them, tyre 200 kN/m from the wheel to the road (base input 0) or to the ground; the outputs chosen
/// by name from [`QuarterCarText::outputs`]. Build it up and take the scenario text with
/// [`QuarterCarText::text`].
pub fn quarter_car_scenario() -> QuarterCarText {
    QuarterCarText {
        title: None,
        road: true,
        force: false,
        outputs: vec!["body", "travel"],
        rest: String::new(),
    }
}

/// A quarter-car scenario text being built ([`quarter_car_scenario`]).
#[derive(Debug, Clone)]
pub struct QuarterCarText {
    title: Option<String>,
    road: bool,
    force: bool,
    outputs: Vec<&'static str>,
    rest: String,
}

impl QuarterCarText {
    /// A `title` line at the top.
    pub fn title(mut self, title: &str) -> Self {
        self.title = Some(title.to_string());
        self
    }

    /// A force input on the body (`forces = [[1, 0]]`): the model input after the base inputs.
    pub fn force(mut self) -> Self {
        self.force = true;
        self
    }

    /// The tyre on the ground instead of on a road: no base input.
    pub fn tyre_on_ground(mut self) -> Self {
        self.road = false;
        self
    }

    /// The `[[model.output]]` tables, by name: `body` (displacement), `body_acc` (acceleration), `travel`
    /// (the suspension's deflection), `tyre_force` (the tyre's spring force). Default `body`, `travel`.
    pub fn outputs(mut self, names: &[&'static str]) -> Self {
        self.outputs = names.to_vec();
        self
    }

    /// Text after the model: the inputs, the analysis, …
    pub fn then(mut self, rest: &str) -> Self {
        self.rest.push_str(rest);
        self
    }

    /// The scenario text.
    pub fn text(&self) -> String {
        let mut t = String::new();
        if let Some(title) = &self.title {
            t.push_str(&format!("title = \"{title}\"\n"));
        }
        t.push_str("[model]\nkind = \"mdof\"\n");
        if self.road {
            t.push_str("base_inputs = 1\n");
        }
        if self.force {
            t.push_str("forces = [[1, 0]]\n");
        }
        t.push_str(
            "coordinates = [{ name = \"body\", mass = \"300 kg\" }, { name = \"wheel\", mass = \"40 kg\" }]\n\
             [[model.element]]\nname = \"suspension\"\npoint = [1, 0]\nto = [0, 1]\nstiffness = \"20 kN/m\"\n\
             damping = \"1.5 kN*s/m\"\n[[model.element]]\nname = \"tyre\"\npoint = [0, 1]\n",
        );
        t.push_str(if self.road {
            "to = \"base 0\"\n"
        } else {
            "to = \"ground\"\n"
        });
        t.push_str("stiffness = \"200 kN/m\"\n");
        for name in &self.outputs {
            let what = match *name {
                "body" => "quantity = \"displacement\"\npoint = [1, 0]",
                "body_acc" => "quantity = \"acceleration\"\npoint = [1, 0]",
                "travel" => "quantity = \"deflection\"\nelement = \"suspension\"",
                "tyre_force" => "quantity = \"spring-force\"\nelement = \"tyre\"",
                other => panic!("no quarter-car output `{other}`"),
            };
            t.push_str(&format!("[[model.output]]\nname = \"{name}\"\n{what}\n"));
        }
        t.push_str(&self.rest);
        t
    }
}

/// A body in bounce z (800 kg) and roll φ (300 kg m²) on two wheels 0.75 m either side of its centre
/// (30 kN/m and 2 kN s/m each, base inputs 0 and 1), with the `[model]` lines `tracks` and
/// `gains = {gains}`, both wheels at 0 m, the outputs `bounce` and `roll`, then `input`.
pub fn two_wheels(tracks: &str, gains: &str, input: &str) -> String {
    format!(
        r#"[model]
kind = "mdof"
base_inputs = 2
{tracks}
gains = {gains}
positions = ["0 m", "0 m"]
coordinates = [
  {{ name = "z", unit = "m", mass = "800 kg" }},
  {{ name = "phi", unit = "rad", mass = "300 kg*m^2" }},
]
[[model.element]]
name = "left"
point = [1, 0.75]
to = "base 0"
stiffness = "30 kN/m"
damping = "2 kN*s/m"
[[model.element]]
name = "right"
point = [1, -0.75]
to = "base 1"
stiffness = "30 kN/m"
damping = "2 kN*s/m"
[[model.output]]
name = "bounce"
quantity = "displacement"
point = [1, 0]
[[model.output]]
name = "roll"
quantity = "displacement"
point = [0, 1]
{input}
"#
    )
}
