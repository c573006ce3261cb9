//! The desync locator: where two snapshots first differ.

use core::fmt;

use super::layout::Layout;
use crate::error::Error;

/// Which object of the state a difference is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Object {
    /// World-wide data: step count, settings, paths, allocator states.
    World,
    /// The body in this slot.
    Body(u32),
    /// The slot of the world's shape store with this index, which holds one
    /// shape of a compound body (see [`crate::compound`]).
    Shape(u32),
    /// The force generator in this slot.
    Generator(u32),
    /// The arbiter of the bodies in these two slots (lower first).
    Arbiter(u32, u32),
    /// The joint in this slot.
    Joint(u32),
}

/// The first difference between two snapshots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Difference {
    /// Where.
    pub object: Object,
    /// Which field, e.g. `"position.x"` or `"normal impulse"`.
    pub field: &'static str,
}

impl fmt::Display for Difference {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.object {
            Object::World => write!(f, "world: {}", self.field),
            Object::Body(i) => write!(f, "body in slot {i}: {}", self.field),
            Object::Shape(i) => write!(f, "shape in slot {i}: {}", self.field),
            Object::Generator(i) => write!(f, "force generator in slot {i}: {}", self.field),
            Object::Arbiter(a, b) => write!(f, "arbiter of bodies {a} and {b}: {}", self.field),
            Object::Joint(i) => write!(f, "joint in slot {i}: {}", self.field),
        }
    }
}

/// Compares two snapshots (e.g. from two peers after the same frame) and names
/// the first object and field that differ, in encoding order; `Ok(None)` when
/// they are equal. Use it when the peers' state hashes disagree.
///
/// # Errors
/// [`Error::InvalidSnapshot`] when either buffer is not a valid snapshot.
pub fn diff(a: &[u8], b: &[u8]) -> Result<Option<Difference>, Error> {
    let (la, lb) = (Layout::parse(a)?, Layout::parse(b)?);
    let found = |object, field| Ok(Some(Difference { object, field }));
    if la.step_count != lb.step_count {
        return found(Object::World, "step count");
    }
    if la.def != lb.def {
        return found(Object::World, "world definition");
    }
    if la.paths != lb.paths {
        return found(Object::World, "polygon paths");
    }
    if la.bodies != lb.bodies {
        return found(Object::World, "body allocator");
    }
    for i in 0..la.bodies.used {
        let (ra, rb) = (la.body(i)?, lb.body(i)?);
        let object = Object::Body(i);
        if ra.live() != rb.live() {
            return found(object, "exists");
        }
        if ra.generation != rb.generation {
            return found(object, "generation");
        }
        if !ra.live() {
            if ra.index() != rb.index() {
                return found(object, "free-list link");
            }
            continue;
        }
        let fields = [
            (ra.position.x != rb.position.x, "position.x"),
            (ra.position.y != rb.position.y, "position.y"),
            (ra.rotation != rb.rotation, "rotation"),
            (ra.linear_velocity.x != rb.linear_velocity.x, "linear velocity.x"),
            (ra.linear_velocity.y != rb.linear_velocity.y, "linear velocity.y"),
            (ra.angular_velocity != rb.angular_velocity, "angular velocity"),
            (ra.out_of_bounds() != rb.out_of_bounds(), "out of bounds"),
        ];
        if let Some((_, field)) = fields.iter().find(|(differs, _)| *differs) {
            return found(object, field);
        }
        let (pa, pb) = (la.props(ra.index())?, lb.props(rb.index())?);
        let fields = [
            (pa.shape != pb.shape, "shape"),
            (pa.body_type != pb.body_type, "body type"),
            (pa.mass != pb.mass, "mass"),
            (pa.inertia != pb.inertia, "inertia"),
            (pa.friction != pb.friction, "friction"),
            (pa.restitution != pb.restitution, "restitution"),
            (pa.groups != pb.groups, "collision groups"),
            (pa.level != pb.level, "collision level"),
            (pa.user_data != pb.user_data, "user data"),
            (pa.bullet != pb.bullet, "bullet"),
            (pa.fixed_rotation != pb.fixed_rotation, "fixed rotation"),
            (pa.linear_damping != pb.linear_damping, "linear damping"),
            (pa.angular_damping != pb.angular_damping, "angular damping"),
            (pa.gravity_scale != pb.gravity_scale, "gravity scale"),
            (pa.filter != pb.filter, "collision filter"),
        ];
        if let Some((_, field)) = fields.iter().find(|(differs, _)| *differs) {
            return found(object, field);
        }
    }
    if let Some(d) = diff_shapes(&la, &lb)? {
        return Ok(Some(d));
    }
    if la.generators != lb.generators {
        return found(Object::World, "generator allocator");
    }
    for (i, (ga, gb)) in la.generators().zip(lb.generators()).enumerate() {
        let (ga, gb) = (ga?, gb?);
        let object = Object::Generator(i as u32);
        if ga.generation != gb.generation || ga.next != gb.next {
            return found(object, "slot");
        }
        if ga.generator != gb.generator {
            return found(object, "parameters");
        }
    }
    if la.arbiters != lb.arbiters {
        return found(Object::World, "arbiter count");
    }
    for i in 0..la.arbiters {
        let (aa, ab) = (la.arbiter(i)?, lb.arbiter(i)?);
        let (x, y, _) = aa.key();
        let object = Object::Arbiter(x, y);
        let fields = [
            (aa.key() != ab.key() || aa.a != ab.a || aa.b != ab.b, "bodies, chain link or shapes"),
            (aa.state != ab.state, "state"),
            (aa.steps_separated != ab.steps_separated, "steps since separation"),
            (aa.count != ab.count, "contact point count"),
            (aa.points.iter().zip(&ab.points).any(|(p, q)| p.id != q.id), "feature id"),
            (
                aa.points.iter().zip(&ab.points).any(|(p, q)| p.normal_impulse != q.normal_impulse),
                "normal impulse",
            ),
            (
                aa.points.iter().zip(&ab.points).any(|(p, q)| p.tangent_impulse != q.tangent_impulse),
                "friction impulse",
            ),
            (aa.manifold != ab.manifold, "cached manifold"),
        ];
        if let Some((_, field)) = fields.iter().find(|(differs, _)| *differs) {
            return found(object, field);
        }
    }
    if la.joints != lb.joints {
        return found(Object::World, "joint allocator");
    }
    for i in 0..la.joints.used {
        let (ja, jb) = (la.joint(i)?, lb.joint(i)?);
        let object = Object::Joint(i);
        if ja.generation != jb.generation || ja.next != jb.next || ja.joint.is_some() != jb.joint.is_some() {
            return found(object, "slot");
        }
        if let (Some(x), Some(y)) = (ja.joint, jb.joint) {
            let fields = [
                (x.def != y.def, "definition"),
                (x.reference != y.reference, "reference angle"),
                (x.impulse != y.impulse, "impulse"),
                (x.angular_impulse != y.angular_impulse, "angular impulse"),
                (x.motor_impulse != y.motor_impulse, "motor impulse"),
                (x.limit_impulse != y.limit_impulse, "limit impulse"),
            ];
            if let Some((_, field)) = fields.iter().find(|(differs, _)| *differs) {
                return found(object, field);
            }
        }
    }
    Ok(None)
}

/// The first difference in the shapes sections (the shape store and the
/// compound bodies' list heads).
fn diff_shapes(la: &Layout<'_>, lb: &Layout<'_>) -> Result<Option<Difference>, Error> {
    let found = |object, field| Ok(Some(Difference { object, field }));
    let (Some(sa), Some(sb)) = (la.shapes, lb.shapes) else {
        return if la.shapes.is_some() == lb.shapes.is_some() {
            Ok(None)
        } else {
            found(Object::World, "shape store")
        };
    };
    if sa.alloc != sb.alloc {
        return found(Object::World, "shape allocator");
    }
    for i in 0..sa.alloc.used {
        let (ra, rb) = (la.shape(i)?, lb.shape(i)?);
        let object = Object::Shape(i);
        if ra.data.is_some() != rb.data.is_some() {
            return found(object, "exists");
        }
        let fields = [
            (ra.generation != rb.generation, "generation"),
            (ra.link != rb.link, "free-list link"),
            (ra.owner != rb.owner, "owner"),
            (ra.next != rb.next, "next shape"),
        ];
        if let Some((_, field)) = fields.iter().find(|(differs, _)| *differs) {
            return found(object, field);
        }
        let (Some(a), Some(b)) = (ra.data, rb.data) else { continue };
        let fields = [
            (a.shape != b.shape, "shape"),
            (a.local.p != b.local.p, "offset"),
            (a.local.q != b.local.q, "rotation"),
            (a.mass != b.mass, "mass"),
            (a.inertia != b.inertia, "inertia"),
            (a.friction != b.friction, "friction"),
            (a.restitution != b.restitution, "restitution"),
            (a.filter != b.filter, "collision filter"),
            (a.sensor != b.sensor, "sensor"),
        ];
        if let Some((_, field)) = fields.iter().find(|(differs, _)| *differs) {
            return found(object, field);
        }
    }
    if sa.compounds != sb.compounds {
        return found(Object::World, "compound body count");
    }
    for k in 0..sa.compounds {
        let ((ba, ha), (bb, hb)) = (la.compound(k)?, lb.compound(k)?);
        if ba != bb {
            return found(Object::Body(ba.min(bb)), "compound or not");
        }
        if ha != hb {
            return found(Object::Body(ba), "first shape slot");
        }
    }
    Ok(None)
}
