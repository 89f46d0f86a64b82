//! Reads the Rust side of the twins with `syn`: every function of `src/` (free functions
//! and the methods of `impl` blocks, not those of inline modules such as `mod tests`),
//! the calls in its body in the order they run (arguments before the call that takes
//! them, a method's receiver before its arguments, as naga orders WGSL's calls), and
//! each file's `use` declarations, which say what a bare name in a call stands for.

use std::collections::{BTreeMap, HashMap};
use std::hash::{DefaultHasher, Hash, Hasher};
use std::sync::Mutex;
use syn::visit::Visit;

/// A call in a Rust function body, before it is resolved to a function of `src/`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Call {
    /// `f(…)`, `module::f(…)`, `Type::f(…)`, `Self::f(…)`: the path's segments.
    Path(Vec<String>),
    /// `receiver.f(…)`: the method's name, and the receiver's type where the body says
    /// it; syn knows no other types.
    Method(String, Option<Receiver>),
}

/// What a body says of a local name's type.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Receiver {
    /// `self`, a parameter or a `let` with a type, a `let` of `Type::f(…)`,
    /// `Type { … }` or `Type::CONSTANT`.
    Type(String),
    /// A `let` of `f(…)`: what the function of that path returns.
    ReturnOf(Vec<String>),
}

/// A call and whether it runs whenever its function runs (not inside a branch, a loop, a
/// closure or the right side of `&&`/`||`): the calls whose order is compared.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RustCall {
    pub call: Call,
    pub fixed: bool,
}

/// One Rust function.
#[derive(Clone, Debug)]
pub struct RustFunction {
    /// `name`, or `Type::name` for a member of `impl Type` (the key of twin comments).
    pub key: String,
    pub calls: Vec<RustCall>,
    /// The name of the type it returns (`Self` as the impl's type), if a path.
    pub returns: Option<String>,
}

/// Everything read from one Rust file.
#[derive(Clone, Debug, Default)]
pub struct RustFile {
    pub functions: Vec<RustFunction>,
    /// Each name a `use` brings in (`use super::ray::{offset_ray, Ray as R}` gives
    /// `offset_ray` → `super::ray::offset_ray` and `R` → `super::ray::Ray`), and for a
    /// glob (`use super::ray::*`) the key `*` with one path per glob.
    pub uses: HashMap<String, Vec<Vec<String>>>,
}

/// Collects the calls of one function body.
#[derive(Default)]
struct CallCollector {
    calls: Vec<RustCall>,
    /// Local names whose type the body says.
    types: HashMap<String, Receiver>,
    /// How many branches, loops and closures enclose the expression being visited.
    conditional: usize,
    /// The type of the `impl` block the function is in (what `Self` names).
    self_type: Option<String>,
}

/// The type a `let` gives its name from its initialiser: `Type::f(…)`, `Type { … }`,
/// `Type::CONSTANT`, or what `f(…)` returns.
fn type_of_init(init: &syn::Expr) -> Option<Receiver> {
    let path = match init {
        syn::Expr::Call(c) => match &*c.func {
            syn::Expr::Path(p) => &p.path,
            _ => return None,
        },
        syn::Expr::Struct(s) => return last_ident(&s.path).map(Receiver::Type),
        syn::Expr::Path(p) => &p.path,
        _ => return None,
    };
    let segments: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
    let n = segments.len();
    if n >= 2 && segments[n - 2].starts_with(|c: char| c.is_uppercase()) {
        return Some(Receiver::Type(segments[n - 2].clone()));
    }
    matches!(init, syn::Expr::Call(_)).then_some(Receiver::ReturnOf(segments))
}

fn last_ident(path: &syn::Path) -> Option<String> {
    path.segments.last().map(|s| s.ident.to_string())
}

/// The name of a type as written, references and `mut` set aside.
fn type_name(ty: &syn::Type) -> Option<String> {
    match ty {
        syn::Type::Path(p) => last_ident(&p.path),
        syn::Type::Reference(r) => type_name(&r.elem),
        _ => None,
    }
}

impl CallCollector {
    fn push(&mut self, call: Call) {
        let fixed = self.conditional == 0;
        self.calls.push(RustCall { call, fixed });
    }

    fn conditionally(&mut self, visit: impl FnOnce(&mut CallCollector)) {
        self.conditional += 1;
        visit(self);
        self.conditional -= 1;
    }

    /// The receiver's type, where the body says it.
    fn receiver_type(&self, receiver: &syn::Expr) -> Option<Receiver> {
        match receiver {
            syn::Expr::Path(p) => {
                let ty = self.types.get(&p.path.get_ident()?.to_string())?;
                match ty {
                    Receiver::Type(t) if t == "Self" => self.self_type.clone().map(Receiver::Type),
                    _ => Some(ty.clone()),
                }
            }
            syn::Expr::Reference(r) => self.receiver_type(&r.expr),
            syn::Expr::Paren(p) => self.receiver_type(&p.expr),
            _ => None,
        }
    }
}

impl<'ast> Visit<'ast> for CallCollector {
    fn visit_expr_call(&mut self, call: &'ast syn::ExprCall) {
        for arg in &call.args {
            self.visit_expr(arg);
        }
        match &*call.func {
            syn::Expr::Path(path) => self.push(Call::Path(
                path.path
                    .segments
                    .iter()
                    .map(|s| s.ident.to_string())
                    .collect(),
            )),
            other => self.visit_expr(other),
        }
    }

    fn visit_expr_method_call(&mut self, call: &'ast syn::ExprMethodCall) {
        self.visit_expr(&call.receiver);
        for arg in &call.args {
            self.visit_expr(arg);
        }
        let receiver = self.receiver_type(&call.receiver);
        self.push(Call::Method(call.method.to_string(), receiver));
    }

    fn visit_local(&mut self, local: &'ast syn::Local) {
        if let Some(init) = &local.init {
            self.visit_expr(&init.expr);
            if let Some((_, diverge)) = &init.diverge {
                self.conditionally(|c| c.visit_expr(diverge));
            }
        }
        let (pat, annotated) = match &local.pat {
            syn::Pat::Type(t) => (&*t.pat, type_name(&t.ty)),
            other => (other, None),
        };
        if let syn::Pat::Ident(name) = pat {
            let ty = annotated
                .map(Receiver::Type)
                .or_else(|| local.init.as_ref().and_then(|i| type_of_init(&i.expr)));
            match ty {
                Some(ty) => self.types.insert(name.ident.to_string(), ty),
                None => self.types.remove(&name.ident.to_string()),
            };
        }
    }

    fn visit_expr_if(&mut self, e: &'ast syn::ExprIf) {
        self.visit_expr(&e.cond);
        self.conditionally(|c| {
            c.visit_block(&e.then_branch);
            if let Some((_, other)) = &e.else_branch {
                c.visit_expr(other);
            }
        });
    }

    fn visit_expr_match(&mut self, e: &'ast syn::ExprMatch) {
        self.visit_expr(&e.expr);
        self.conditionally(|c| {
            for arm in &e.arms {
                c.visit_arm(arm);
            }
        });
    }

    fn visit_expr_for_loop(&mut self, e: &'ast syn::ExprForLoop) {
        self.visit_expr(&e.expr);
        self.conditionally(|c| c.visit_block(&e.body));
    }

    fn visit_expr_while(&mut self, e: &'ast syn::ExprWhile) {
        self.conditionally(|c| {
            c.visit_expr(&e.cond);
            c.visit_block(&e.body);
        });
    }

    fn visit_expr_loop(&mut self, e: &'ast syn::ExprLoop) {
        self.conditionally(|c| c.visit_block(&e.body));
    }

    fn visit_expr_closure(&mut self, e: &'ast syn::ExprClosure) {
        self.conditionally(|c| c.visit_expr(&e.body));
    }

    fn visit_expr_binary(&mut self, e: &'ast syn::ExprBinary) {
        self.visit_expr(&e.left);
        match e.op {
            syn::BinOp::And(_) | syn::BinOp::Or(_) => {
                self.conditionally(|c| c.visit_expr(&e.right))
            }
            _ => self.visit_expr(&e.right),
        }
    }

    // A function declared inside a body is a function of its own, not a step.
    fn visit_item_fn(&mut self, _: &'ast syn::ItemFn) {}
}

/// The calls of a function with signature `sig` and body `block`, in `impl self_type`.
fn calls_of(sig: &syn::Signature, block: &syn::Block, self_type: Option<&str>) -> Vec<RustCall> {
    let mut collector = CallCollector {
        self_type: self_type.map(str::to_string),
        ..CallCollector::default()
    };
    for input in &sig.inputs {
        match input {
            syn::FnArg::Receiver(_) => {
                if let Some(ty) = self_type {
                    collector
                        .types
                        .insert("self".into(), Receiver::Type(ty.to_string()));
                }
            }
            syn::FnArg::Typed(t) => {
                if let (syn::Pat::Ident(name), Some(ty)) = (&*t.pat, type_name(&t.ty)) {
                    collector
                        .types
                        .insert(name.ident.to_string(), Receiver::Type(ty));
                }
            }
        }
    }
    collector.visit_block(block);
    collector.calls
}

/// Adds the names a `use` tree brings in, under `prefix`.
fn add_uses(
    tree: &syn::UseTree,
    prefix: &mut Vec<String>,
    uses: &mut HashMap<String, Vec<Vec<String>>>,
) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            add_uses(&p.tree, prefix, uses);
            prefix.pop();
        }
        syn::UseTree::Name(n) => {
            let mut path = prefix.clone();
            path.push(n.ident.to_string());
            uses.entry(n.ident.to_string()).or_default().push(path);
        }
        syn::UseTree::Rename(r) => {
            let mut path = prefix.clone();
            path.push(r.ident.to_string());
            uses.entry(r.rename.to_string()).or_default().push(path);
        }
        syn::UseTree::Glob(_) => uses.entry("*".into()).or_default().push(prefix.clone()),
        syn::UseTree::Group(g) => {
            for item in &g.items {
                add_uses(item, prefix, uses);
            }
        }
    }
}

/// The type `sig` returns, `Self` as `self_type`.
fn return_type(sig: &syn::Signature, self_type: Option<&str>) -> Option<String> {
    let syn::ReturnType::Type(_, ty) = &sig.output else {
        return None;
    };
    let name = type_name(ty)?;
    match name.as_str() {
        "Self" => self_type.map(str::to_string),
        _ => Some(name),
    }
}

/// Reads one Rust file; an error when syn cannot parse it.
pub fn read_file(text: &str) -> Result<RustFile, String> {
    let file = syn::parse_file(text).map_err(|e| e.to_string())?;
    let mut out = RustFile::default();
    for item in &file.items {
        match item {
            syn::Item::Fn(f) => out.functions.push(RustFunction {
                key: f.sig.ident.to_string(),
                calls: calls_of(&f.sig, &f.block, None),
                returns: return_type(&f.sig, None),
            }),
            syn::Item::Impl(i) => {
                let Some(ty) = type_name(&i.self_ty) else {
                    continue;
                };
                for member in &i.items {
                    if let syn::ImplItem::Fn(f) = member {
                        out.functions.push(RustFunction {
                            key: format!("{ty}::{}", f.sig.ident),
                            calls: calls_of(&f.sig, &f.block, Some(&ty)),
                            returns: return_type(&f.sig, Some(&ty)),
                        });
                    }
                }
            }
            syn::Item::Use(u) => add_uses(&u.tree, &mut Vec::new(), &mut out.uses),
            _ => {}
        }
    }
    Ok(out)
}

/// Reads every `.rs` file of `texts` (repository path, text), by path; files syn cannot
/// parse are listed with the error.
pub fn read(texts: &[(String, String)]) -> (BTreeMap<String, RustFile>, Vec<String>) {
    let mut files = BTreeMap::new();
    let mut problems = Vec::new();
    // Each text is parsed once (the tests that edit one file reuse the others').
    static READ: Mutex<BTreeMap<(String, u64), Result<RustFile, String>>> =
        Mutex::new(BTreeMap::new());
    for (path, text) in texts.iter().filter(|(p, _)| p.ends_with(".rs")) {
        let mut hasher = DefaultHasher::new();
        text.hash(&mut hasher);
        let key = (path.clone(), hasher.finish());
        let cached = READ.lock().unwrap().get(&key).cloned();
        let read = cached.unwrap_or_else(|| {
            let read = read_file(text);
            READ.lock().unwrap().insert(key, read.clone());
            read
        });
        match read {
            Ok(file) => {
                files.insert(path.clone(), file);
            }
            Err(e) => problems.push(format!("{path}: syn cannot parse it: {e}")),
        }
    }
    (files, problems)
}
