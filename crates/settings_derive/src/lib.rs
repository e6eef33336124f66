//! `#[derive(Settings)]`: a struct of typed settings whose fields name their parameter declarations.
//!
//! ```ignore
//! #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
//! pub struct Settings {
//!     /// Trials per cell.
//!     #[param(TRIALS)]
//!     pub trials: u64,
//!     /// The gearing, h and G.
//!     #[group]
//!     pub gearing: study::gearing::GearingParams,
//! }
//! ```
//!
//! writes `impl registry::Settings for Settings`: its parameter table (every `#[param(DECL)]`
//! field's declaration and every `#[group]` field's table, in field order), a reader that takes
//! each field from the run's checked values by its declaration, and the fields that differ from
//! their defaults. A field with neither attribute is refused: every setting is a parameter or a
//! group of them, so that nothing is set that `--set` and `help` do not show.
//!
//! `#[settings(check = path)]` on the struct names a check across fields,
//! `fn(&Self, &registry::Context) -> Result<(), registry::RunError>`, run once the fields are
//! read (a grid's end below its start names the parameter the user set).

use proc_macro::TokenStream;
use proc_macro2::TokenStream as Tokens;
use quote::quote;
use syn::{Data, DeriveInput, Expr, Fields, Ident, parse_macro_input};

/// One field of the struct: what it is read as.
enum Field {
    /// `#[param(DECL)]`: one parameter, read by its declaration `DECL` (a `registry::Param`).
    Param(Ident, Expr),
    /// `#[group]`: a nested struct of settings, its table spliced in.
    Group(Ident, syn::Type),
}

/// See the crate documentation.
#[proc_macro_derive(Settings, attributes(param, group, settings))]
pub fn derive_settings(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    match expand(&input) {
        Ok(tokens) => tokens.into(),
        Err(e) => e.to_compile_error().into(),
    }
}

fn fields(input: &DeriveInput) -> syn::Result<Vec<Field>> {
    let Data::Struct(data) = &input.data else {
        return Err(syn::Error::new_spanned(
            &input.ident,
            "Settings can only be derived for a struct with named fields",
        ));
    };
    let Fields::Named(named) = &data.fields else {
        return Err(syn::Error::new_spanned(
            &input.ident,
            "Settings can only be derived for a struct with named fields",
        ));
    };
    named
        .named
        .iter()
        .map(|f| {
            let Some(name) = f.ident.clone() else {
                return Err(syn::Error::new_spanned(f, "a field needs a name"));
            };
            for attr in &f.attrs {
                if attr.path().is_ident("param") {
                    return Ok(Field::Param(name, attr.parse_args::<Expr>()?));
                }
                if attr.path().is_ident("group") {
                    return Ok(Field::Group(name, f.ty.clone()));
                }
            }
            Err(syn::Error::new_spanned(
                f,
                "every field of a Settings struct is `#[param(DECLARATION)]` or `#[group]`",
            ))
        })
        .collect()
}

/// The `check = path` of a `#[settings(...)]` attribute, if any.
fn check_fn(input: &DeriveInput) -> syn::Result<Option<syn::Path>> {
    let mut check = None;
    for attr in input.attrs.iter().filter(|a| a.path().is_ident("settings")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("check") {
                check = Some(meta.value()?.parse::<syn::Path>()?);
                Ok(())
            } else {
                Err(meta.error("expected `check = path`"))
            }
        })?;
    }
    Ok(check)
}

fn expand(input: &DeriveInput) -> syn::Result<Tokens> {
    let fields = fields(input)?;
    let check = check_fn(input)?.map(|f| quote! { #f(&settings, values)?; });
    let ident = &input.ident;
    let (imp, ty, whr) = input.generics.split_for_impl();
    let params = fields.iter().map(|f| match f {
        Field::Param(_, decl) => quote! { out.push(&#decl); },
        Field::Group(_, t) => quote! { <#t as ::registry::Settings>::params(out); },
    });
    let reads = fields.iter().map(|f| match f {
        Field::Param(name, decl) => quote! { #name: values.get(&#decl)?, },
        Field::Group(name, t) => {
            quote! { #name: <#t as ::registry::Settings>::read(values)?, }
        }
    });
    let changed = fields.iter().map(|f| match f {
        Field::Param(name, decl) => {
            quote! { ::registry::changed_from_default(&#decl, &self.#name, out); }
        }
        Field::Group(name, _) => quote! { ::registry::Settings::changed(&self.#name, out); },
    });
    Ok(quote! {
        impl #imp ::registry::Settings for #ident #ty #whr {
            fn params(out: &mut ::std::vec::Vec<&'static ::registry::Param>) {
                #(#params)*
            }
            fn read(values: &::registry::Context) -> ::std::result::Result<Self, ::registry::RunError> {
                let settings = Self { #(#reads)* };
                #check
                ::std::result::Result::Ok(settings)
            }
            fn changed(&self, out: &mut ::std::vec::Vec<(&'static ::registry::Param, ::std::string::String)>) {
                #(#changed)*
            }
        }
    })
}
