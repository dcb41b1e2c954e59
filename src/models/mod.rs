//! The model catalogue of the source documents: each model is a constructor from physical parameters
//! with its equations, units and source section in its doc comment, one model per file.
//!
//! Stochastic models produce a [`ModelInstance`] (a system plus the layout of its random inputs) that the
//! scenario files and the `analyze` / `simulate` commands use; every model also contributes rows to the
//! `book` report ([`crate::report::book`]).
//!
//! # Sources
//!
//! Everywhere else in the crate the sources are cited by the short form in bold, followed by the section,
//! equation, table, example or figure number as printed in the source.
//!
//! - **Sukharev (2012)**: Сухарев Э.А. *Основы динамики подъемно-транспортных и дорожно-строительных
//!   машин* (Fundamentals of the dynamics of lifting-transport and road-construction machines): учебное
//!   пособие (textbook). Rivne: National University of Water Management and Nature Resources Use (НУВХП),
//!   2012. 191 pp. UDC 531.3:621.86:69.002.5. In Russian. Used: chapter 7 (vibration isolation 7.1, 7.2;
//!   half-car suspension 7.5, Example 7.1; operator seat and sanitary norms 7.6, Table 7.1, Example 7.2) and
//!   chapter 8 (random processes 8.2–8.4; balancer bogie 8.5; conveyor idler 8.6, Example 8.1; scraper 8.7,
//!   Table 8.1). The book numbers two examples "Example 7.2": the excavator resonance speed in 7.5
//!   (Fig. 7.7) and the operator seat in 7.6; this crate calls the first one "the excavator example of 7.5".
//! - **Ofiy & Rakhmaniy (2010)**: Офій В.В., Рахманий А.С. *Визначення динамічних навантажень в
//!   тримасових системах* (Determination of dynamic loads in three-mass systems). Kharkiv: National
//!   Technical University "Kharkiv Polytechnic Institute" (НТУ «ХПІ»), 2010; received by the editors
//!   28.09.2010. In Ukrainian. The article's pages print no journal name or issue. The first author is
//!   spelled as in the byline ("В.В. ОФІЙ"); the article's own reference list has "Офиц В. В.".
//! - **Yurchenko (2011)**: Юрченко О.О. *Розрахунок лінійних коливань механічних систем методом
//!   динамічних жорсткостей* (Calculation of linear vibrations of mechanical systems by the
//!   dynamic-stiffness method). Kharkiv: Ivan Kozhedub Kharkiv University of the Air Force, 2011; received
//!   by the editors 14.11.2011. UDC 531/534:001.8. In Ukrainian. The article's pages print no journal name.
//! - **Dvornikov, Kondrakhin & Velebnik (2014)**: Дворников В.И., Кондрахин В.П., Велебник С.В.
//!   *Собственные частоты и формы колебаний одноконцевой подъемной машины* (English title as printed:
//!   Natural frequencies and mode shapes of lifting machine with one end). Donetsk National Technical
//!   University, 2014; received by the editors 21.05.2014. In Russian. The article's pages print no
//!   journal name.

mod instance;

pub use instance::{InputLayout, ModelInstance};

pub mod balancer_bogie;
pub mod conveyor_idler;
pub mod dynamic_stiffness_chain;
pub mod full_vehicle;
pub mod half_car;
pub mod isolation;
pub mod machine_assembly;
pub mod mine_hoist;
pub mod operator_seat;
pub mod quarter_car;
pub mod results;
pub mod scraper;
pub mod three_mass_hoist;
pub mod worked_example;
