//! The configuration data of a Cartesian target: each language states its own type in its
//! folder (its [`crate::program::Controller::Flags`], implementing [`ConfigurationData`], from
//! the posture's [`stiffid_core::robot::configuration`]); the shared code (the solve, the
//! writing back) holds them as [`Flags`] and each part's form as `Part`, whatever the
//! language.

use std::any::Any;
use std::fmt;
use stiffid_core::robot::configuration::Configuration;

/// The shoulder, elbow and wrist a posture or configuration data name, as
/// [`stiffid_core::robot::configuration`] reads them: the wrist centre behind axis 1, the elbow
/// down, axis 5 negative (or zero, where the controller counts it so).
pub(crate) type Branch = (bool, bool, bool);

/// A language's configuration data: what picks one of the up to eight inverse-kinematics
/// solutions of a pose, as the controller's manual defines it from the posture.
pub trait ConfigurationData: fmt::Debug + Clone + PartialEq + Send + Sync + 'static {
    /// How one part of the data is written where a program states it (KRL's status as a
    /// binary string or a number); `()` where the data are written whole.
    type Part: fmt::Debug + Copy + PartialEq + Send + Sync + 'static;
    /// The data's name in the language, for messages (`S and T`).
    const NAME: &'static str;
    /// The data of the posture `arm`.
    fn of(arm: &Configuration) -> Self;
    /// The shoulder, elbow and wrist they name.
    fn branch(&self) -> Branch;
    /// As the program writes them, for messages.
    fn text(&self) -> String;
    /// The text of `part` of the data, where a program holds it.
    fn part(&self, part: Self::Part) -> String;
}

/// The configuration data of a language without its own (its Cartesian targets are not read):
/// the shoulder, elbow and wrist of the posture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Posture(pub Branch);

impl ConfigurationData for Posture {
    type Part = ();
    const NAME: &'static str = "shoulder, elbow and wrist";
    fn of(arm: &Configuration) -> Self {
        Posture((arm.behind(), arm.elbow_down(), arm.wrist_negative()))
    }
    fn branch(&self) -> Branch {
        self.0
    }
    fn text(&self) -> String {
        let (behind, down, negative) = self.0;
        format!(
            "{}, elbow {}, axis 5 {}",
            if behind { "back" } else { "front" },
            if down { "down" } else { "up" },
            if negative { "negative" } else { "positive" }
        )
    }
    fn part(&self, _part: ()) -> String {
        ConfigurationData::text(self)
    }
}

/// A target's configuration data, of whichever language read or wrote them.
pub struct Flags(Box<dyn Erased>);

impl Flags {
    /// The data `data` of a language.
    pub fn new<F: ConfigurationData>(data: F) -> Self {
        Flags(Box::new(data))
    }

    /// The data of the posture `arm` in `dialect` (its controller's
    /// [`crate::program::Controller::Flags`]).
    pub fn of(dialect: super::super::Dialect, arm: &Configuration) -> Self {
        dialect.controller().flags(arm)
    }

    /// The data as the language's own type `F`, if they are of it.
    #[cfg(test)]
    pub(crate) fn get<F: ConfigurationData>(&self) -> Option<&F> {
        self.0.any().downcast_ref()
    }

    /// The shoulder, elbow and wrist the data name ([`ConfigurationData::branch`]).
    pub fn branch(&self) -> Branch {
        self.0.branch()
    }

    /// As the program writes them (LS `N U T, 0, 0, 0`, RAPID `[0,-1,0,1]`).
    pub fn text(&self) -> String {
        self.0.text()
    }
}

impl Clone for Flags {
    fn clone(&self) -> Self {
        Flags(self.0.boxed())
    }
}

impl PartialEq for Flags {
    fn eq(&self, other: &Self) -> bool {
        self.0.same(other.0.any())
    }
}

impl fmt::Debug for Flags {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

/// Where a part of the data sits and how it is written back: a language's
/// [`ConfigurationData::Part`].
pub(crate) struct Part(Box<dyn ErasedPart>);

impl Part {
    /// The part `part` of a language's data.
    pub(crate) fn new<P: fmt::Debug + Copy + PartialEq + Send + Sync + 'static>(part: P) -> Self {
        Part(Box::new(part))
    }

    /// The text of this part of `flags`; their whole text where they are another language's.
    pub(crate) fn text(&self, flags: &Flags) -> String {
        (flags.0.part(self.0.any())).unwrap_or_else(|| flags.text())
    }
}

impl Clone for Part {
    fn clone(&self) -> Self {
        Part(self.0.boxed())
    }
}

impl PartialEq for Part {
    fn eq(&self, other: &Self) -> bool {
        self.0.same(other.0.any())
    }
}

impl fmt::Debug for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

/// [`ConfigurationData`] without its type.
trait Erased: fmt::Debug + Send + Sync {
    fn branch(&self) -> Branch;
    fn text(&self) -> String;
    fn part(&self, part: &dyn Any) -> Option<String>;
    fn any(&self) -> &dyn Any;
    fn same(&self, other: &dyn Any) -> bool;
    fn boxed(&self) -> Box<dyn Erased>;
}

impl<F: ConfigurationData> Erased for F {
    fn branch(&self) -> Branch {
        ConfigurationData::branch(self)
    }
    fn text(&self) -> String {
        ConfigurationData::text(self)
    }
    fn part(&self, part: &dyn Any) -> Option<String> {
        (part.downcast_ref::<F::Part>()).map(|p| ConfigurationData::part(self, *p))
    }
    fn any(&self) -> &dyn Any {
        self
    }
    fn same(&self, other: &dyn Any) -> bool {
        other.downcast_ref::<F>() == Some(self)
    }
    fn boxed(&self) -> Box<dyn Erased> {
        Box::new(self.clone())
    }
}

/// A [`ConfigurationData::Part`] without its type.
trait ErasedPart: fmt::Debug + Send + Sync {
    fn any(&self) -> &dyn Any;
    fn same(&self, other: &dyn Any) -> bool;
    fn boxed(&self) -> Box<dyn ErasedPart>;
}

impl<P: fmt::Debug + Copy + PartialEq + Send + Sync + 'static> ErasedPart for P {
    fn any(&self) -> &dyn Any {
        self
    }
    fn same(&self, other: &dyn Any) -> bool {
        other.downcast_ref::<P>() == Some(self)
    }
    fn boxed(&self) -> Box<dyn ErasedPart> {
        Box::new(*self)
    }
}
