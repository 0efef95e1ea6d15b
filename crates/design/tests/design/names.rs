//! The design's choices by the names scenes write: each parses its own
//! name back, an unknown name is an error that lists the names there are,
//! and (the `serde` feature) each serializes as its name.

use elcon_design::{Axis, DesignMethod, FamilyKind, LogEnd, Objective};
use elcon_num::unparsed;

#[test]
fn each_choice_parses_its_name() {
    assert_eq!(Axis::NAMES, ["x", "y"]);
    assert_eq!(DesignMethod::NAMES, ["auto", "program", "descent"]);
    assert_eq!(Objective::NAMES, ["pressure", "von-mises", "max-shear"]);
    assert_eq!(unparsed(&Axis::ALL), None);
    assert_eq!(unparsed(&DesignMethod::ALL), None);
    assert_eq!(unparsed(&Objective::ALL), None);
    assert_eq!(
        FamilyKind::NAMES,
        [
            "quadratic",
            "polynomial",
            "free",
            "circular-crown",
            "logarithmic-crown"
        ]
    );
    assert_eq!(unparsed(&FamilyKind::ALL), None);
    for end in LogEnd::NAMED {
        assert_eq!(end.name().parse::<LogEnd>(), Ok(end));
    }
    // Fujiwara & Kawase's end needs its parameters: no name alone gives it.
    let e = "fujiwara-kawase".parse::<LogEnd>().unwrap_err();
    assert_eq!(
        e.to_string(),
        "unknown end `fujiwara-kawase`, expected one of `johns-gohar`, `lundberg`"
    );
}

#[test]
fn an_unknown_name_lists_the_names_there_are() {
    let e = "z".parse::<Axis>().unwrap_err();
    assert_eq!(e.to_string(), "unknown axis `z`, expected one of `x`, `y`");
    let e = "newton".parse::<DesignMethod>().unwrap_err();
    assert_eq!(
        e.to_string(),
        "unknown design method `newton`, expected one of `auto`, `program`, `descent`"
    );
    let e = "tresca".parse::<Objective>().unwrap_err();
    assert_eq!((e.kind, e.allowed), ("objective", &Objective::NAMES[..]));
}

#[cfg(feature = "serde")]
#[test]
fn each_choice_deserializes_from_its_name() {
    use elcon_num::from_name as read;
    assert_eq!(read::<Axis>("y").unwrap(), Axis::Y);
    assert_eq!(
        read::<DesignMethod>("descent").unwrap(),
        DesignMethod::Descent
    );
    assert_eq!(read::<Objective>("von-mises").unwrap(), Objective::VonMises);
    let e = read::<DesignMethod>("newton").unwrap_err().to_string();
    assert_eq!(
        e,
        "unknown variant `newton`, expected one of `auto`, `program`, `descent`"
    );
}

#[test]
fn the_program_reads_entries_and_the_others_take_any_case() {
    for method in DesignMethod::ALL {
        assert_eq!(method.admits(true).unwrap(), method);
    }
    assert_eq!(
        DesignMethod::Auto.admits(false).unwrap(),
        DesignMethod::Auto
    );
    assert_eq!(
        DesignMethod::Descent.admits(false).unwrap(),
        DesignMethod::Descent
    );
    let e = DesignMethod::Program.admits(false).unwrap_err().to_string();
    assert!(
        e.starts_with("`method`: the program reads S's entries"),
        "{e}"
    );
}
